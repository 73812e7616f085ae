#!/usr/bin/env bash
# What the intact rock's sites cost (issue 53): `cdca grow` on steps where
# no crack starts in the intact rock, under growth.intact_rock = "nucleate"
# against "ignore", on one build, run in turn (A B A B ..., medians of
# RUNS each): the paper's confined plate (k = 0.3, 30 load steps, its rock
# can never fail), the default specimen's first two steps (its wings) and
# a held-out 10 mm flaw's first four (its wings). Prints the table, checks
# that the two models grew the same steps, and writes
# bench-out/intact_rock_cost.csv. A benchmark, not a test: times depend on
# the machine and its load.
# Usage: RUNS=5 bash scripts/bench_intact_rock.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q --workspace
mkdir -p bench-out/intact_rock_cost
python3 - <<'PY'
import csv, json, math, os, statistics, subprocess, time

RUNS = int(os.environ.get("RUNS", "5"))
CDCA = "./target/release/cdca"

def scene(name, steps=None, flaw=None):
    s = json.load(open(f"assets/scenes/{name}.json"))
    if steps:
        s["growth"]["max_steps"] = steps
    if flaw:
        length, deg, mu = flaw
        h = s["specimen"]["width"] / s["mesh"]["nx"]
        cx, cy = 0.015 + 0.37 * h, 0.015 + 0.21 * h
        a, t = 0.5 * length, math.radians(deg)
        s["cracks"] = [{"points": [[cx - a * math.cos(t), cy - a * math.sin(t)],
                                   [cx + a * math.cos(t), cy + a * math.sin(t)]],
                        "friction": mu}]
    return s

cases = [
    ("plate k 0.3, mu 0.5 (30 load steps)", scene("plate_45_biaxial_k0.3_mu0.5")),
    ("default specimen, its wings (2 steps)", scene("specimen_single_flaw", 2)),
    ("10 mm flaw at 45 deg, mu 0, its wings (4 steps)", scene("specimen_single_flaw", 4, (0.01, 45, 0.0))),
]
rows = []
print(f"{'scene':48s} {'steps':>5s} {'ignore ms/step':>15s} {'nucleate ms/step':>17s} {'ratio':>6s}  same steps")
for label, s in cases:
    paths = {}
    for model in ("ignore", "nucleate"):
        s["growth"]["intact_rock"] = model
        path = f"bench-out/intact_rock_cost/{len(rows)}_{model}.json"
        json.dump(s, open(path, "w"), indent=1)
        paths[model] = path
    times = {"ignore": [], "nucleate": []}
    reports = {}
    for _ in range(RUNS):
        for model in ("ignore", "nucleate"):
            start = time.perf_counter()
            out = subprocess.run([CDCA, "grow", paths[model]], capture_output=True, text=True).stdout
            times[model].append(time.perf_counter() - start)
            reports[model] = json.loads(out)
    a, b = reports["ignore"], reports["nucleate"]
    assert not any(st.get("nucleated") for st in b["steps"]), f"{label}: a crack started"
    same = [(st["step"], st["load_factor"], st["grown"]) for st in a["steps"]] == \
           [(st["step"], st["load_factor"], st["grown"]) for st in b["steps"]]
    n = len(a["steps"])
    ta, tb = statistics.median(times["ignore"]) / n * 1e3, statistics.median(times["nucleate"]) / n * 1e3
    rows.append([label, n, f"{ta:.1f}", f"{tb:.1f}", f"{tb / ta:.3f}", same])
    print(f"{label:48s} {n:5d} {ta:15.1f} {tb:17.1f} {tb / ta:6.3f}  {same}", flush=True)
with open("bench-out/intact_rock_cost.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["scene", "steps", "ignore_ms_per_step", "nucleate_ms_per_step", "ratio", "same_steps"])
    w.writerows(rows)
print("wrote bench-out/intact_rock_cost.csv")
PY
