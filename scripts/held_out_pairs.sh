#!/usr/bin/env bash
# Held-out flaw pairs (docs/fracture-model.md, "Coalescence"): the bundled stepped and
# overlapping layouts centred in the specimen, then one thing varied at a
# time (offset across or along the load, flaw angle, friction), each grown
# to failure with `cdca grow` (100 × 100, product defaults). Prints one row
# per run (outcome, steps, whether every step converged, the steps at which
# a grown tip ended on the other crack) and writes bench-out/pairs.csv,
# and the summary rows that `bash scripts/docs.sh` puts in docs/.
# Usage: bash scripts/held_out_pairs.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p cdca-cli
mkdir -p bench-out/pairs
python3 - <<'PY'
import csv, json, math, subprocess, sys
sys.path.insert(0, "scripts")
from polyline import on_polyline
base = json.load(open("assets/scenes/specimen_two_flaws_stepped.json"))

def flaw(cx, cy, deg, mu, length=0.003):
    a = math.radians(deg)
    dx, dy = 0.5 * length * math.cos(a), 0.5 * length * math.sin(a)
    return {"points": [[cx - dx, cy - dy], [cx + dx, cy + dy]], "friction": mu}

# (layout, offset across, offset along the load (mm), angle (deg), friction)
runs = [("stepped", 1.6, 5, 45, 0.5), ("stepped", 1.0, 5, 45, 0.5), ("stepped", 2.2, 5, 45, 0.5),
        ("stepped", 1.6, 4, 45, 0.5), ("stepped", 1.6, 6, 45, 0.5), ("stepped", 1.6, 5, 40, 0.5),
        ("stepped", 1.6, 5, 50, 0.5), ("stepped", 1.6, 5, 45, 0.3),
        ("overlapping", 2.8, -1.2, 45, 0.5), ("overlapping", 2.4, -1.2, 45, 0.5),
        ("overlapping", 3.2, -1.2, 45, 0.5), ("overlapping", 2.8, -0.8, 45, 0.5),
        ("overlapping", 2.8, -1.6, 45, 0.5), ("overlapping", 2.8, -1.2, 40, 0.5),
        ("overlapping", 2.8, -1.2, 50, 0.5), ("overlapping", 2.8, -1.2, 45, 0.3)]
rows = []
print(f"{'layout':12s} {'across':>6s} {'along':>6s} {'angle':>5s} {'mu':>4s}  {'outcome':14s} {'steps':>5s} {'converged':>9s}  links at steps")
for layout, dx, dy, deg, mu in runs:
    scene = json.loads(json.dumps(base))
    scene["name"] = f"held-out {layout} pair"
    scene["cracks"] = [flaw(0.015 - dx / 2e3, 0.015 - dy / 2e3, deg, mu),
                       flaw(0.015 + dx / 2e3, 0.015 + dy / 2e3, deg, mu)]
    path = f"bench-out/pairs/{layout}_{dx}_{dy}_{deg}_{mu}.json"
    json.dump(scene, open(path, "w"), indent=1)
    # exit 1 (a step that did not converge) still prints the history
    report = json.loads(subprocess.run(["./target/release/cdca", "grow", path],
                                       capture_output=True, text=True).stdout)
    links = sorted({s["step"] for s in report["steps"] for g in s["grown"]
                    if any(k != g["crack"] and on_polyline((g["x"], g["y"]), c)
                           for k, c in enumerate(report["cracks"]))})
    converged = all(s["converged"] for s in report["steps"])
    rows.append([layout, dx, dy, deg, mu, report["outcome"], len(report["steps"]), converged,
                 " ".join(map(str, links))])
    print(f"{layout:12s} {dx:6.1f} {dy:6.1f} {deg:5d} {mu:4.1f}  {report['outcome']:14s} "
          f"{len(report['steps']):5d} {str(converged):>9s}  {' '.join(map(str, links)) or '-'}", flush=True)
with open("bench-out/pairs.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["layout", "across_mm", "along_mm", "angle_deg", "friction", "outcome", "steps",
                "every_step_converged", "link_steps"])
    w.writerows(rows)
# the summary table of docs/fracture-model.md (*Coalescence*), between its
# markers through `bash scripts/docs.sh`
import os
out = os.path.join(os.environ.get("CARGO_TARGET_DIR", "target"), "docs", "held-out-pairs")
os.makedirs(out, exist_ok=True)
for key, layout in (("1", "stepped"), ("2", "overlapping")):
    runs = [r for r in rows if r[0] == layout]
    firsts = sorted(int(r[8].split()[0]) for r in runs if r[8])
    linked = f"{len(firsts)}"
    if firsts:
        linked += f" (first links at steps {firsts[0]}–{firsts[-1]})" if firsts[0] != firsts[-1] else f" (first link at step {firsts[0]})"
    outcomes = {}
    for r in runs:
        outcomes[r[5]] = outcomes.get(r[5], 0) + 1
    text = ", ".join(f"{n} {o}" for o, n in sorted(outcomes.items(), key=lambda x: (-x[1], x[0])))
    with open(os.path.join(out, f"{key}-{layout}.md"), "w") as f:
        f.write(f"| {layout} | {len(runs)} | {linked} | {sum(r[7] for r in runs)} | {text} |\n")
print(f"wrote bench-out/pairs.csv and {out}/")
PY
