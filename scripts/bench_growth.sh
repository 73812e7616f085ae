#!/usr/bin/env bash
# Growth benchmark (issue 10): runs `cdca grow` on the bundled two-flaw
# specimens (100 × 100, critical control, grown to failure) and prints a table of
# steps, tip extensions, junctions, shear extensions, the λ_cr range, wall
# time and time per step; writes bench-out/growth.csv. A benchmark, not a
# test: times depend on the machine and its load.
# Usage: bash scripts/bench_growth.sh [SCENE.json ...]
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p cdca-cli
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(assets/scenes/specimen_two_flaws_{coplanar,stepped,overlapping}.json)
mkdir -p bench-out
python3 - "${scenes[@]}" <<'PY'
import json, os, subprocess, sys, time
rows = []
for scene in sys.argv[1:]:
    start = time.perf_counter()
    # exit 1 (a step that did not converge) still prints the history
    text = subprocess.run(["./target/release/cdca", "grow", scene], capture_output=True, text=True).stdout
    wall = time.perf_counter() - start
    run = json.loads(text)
    steps = run["steps"]
    grown = [g for s in steps for g in s["grown"]]
    on_crack = lambda g: any(k != g["crack"] and any(
        abs((q[0] - g["x"]) * (r[1] - g["y"]) - (q[1] - g["y"]) * (r[0] - g["x"])) < 1e-12
        and min(q[0], r[0]) - 1e-9 <= g["x"] <= max(q[0], r[0]) + 1e-9
        and min(q[1], r[1]) - 1e-9 <= g["y"] <= max(q[1], r[1]) + 1e-9
        for q, r in zip(c, c[1:])) for k, c in enumerate(run["cracks"]))
    lam = [s["load_factor"] for s in steps if s["grown"]]
    rows.append((os.path.basename(scene), len(steps), len(grown), sum(map(on_crack, grown)),
                 sum(g["mode"] == "shear" for g in grown), min(lam, default=0), max(lam, default=0),
                 float(wall), float(wall) / max(len(steps), 1), run["outcome"]))
head = ("scene", "steps", "extensions", "junctions", "shear", "λ_cr min", "λ_cr max", "wall s", "s/step", "outcome")
print("| " + " | ".join(head) + " |")
print("|" + " --- |" * len(head))
for r in rows:
    print(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]} | {r[4]} | {r[5]:.3f} | {r[6]:.3f} | {r[7]:.2f} | {r[8]:.3f} | {r[9]} |")
with open("bench-out/growth.csv", "w") as f:
    f.write(",".join(h.replace("λ_cr", "lambda_cr").replace(" ", "_") for h in head) + "\n")
    for r in rows:
        f.write(",".join(str(v) for v in r) + "\n")
print("wrote bench-out/growth.csv")
PY
