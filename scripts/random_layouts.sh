#!/usr/bin/env bash
# Random flaw layouts a user might draw (docs/fracture-model.md, "Random layouts"):
# 40 scenes from a fixed seed, each the default specimen with 1–3 closed
# flaws of 2–8 mm at any angle anywhere in its middle, face friction
# 0–1.2 and, on about a third of them, face cohesion 2–15 MPa, grown to
# failure with `cdca grow` (60 × 60, product defaults). Prints one row per
# scene (outcome, steps, whether every step converged, the first growth)
# and a summary, and writes bench-out/random_layouts.csv. MESH sets the
# elements per side, SOLVER the linear solver (direct, automaton, cg,
# multigrid), and LOAD_STEPS=N grows under load control instead: the load
# ramped to 150 MPa in N steps, at most 20 growths per step, 80 steps.
# Its runs of seed 7 are the study assets/studies/random_layouts.json
# (`cdca study`, docs/studies.md); this script stays for other seeds and
# the load-controlled variant, whose draws a study file would have to list.
# Usage: [MESH=60] [SOLVER=direct] [LOAD_STEPS=N] bash scripts/random_layouts.sh [COUNT] [SEED]
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p cdca-cli
mkdir -p bench-out/random_layouts
COUNT="${1:-40}" SEED="${2:-7}" MESH="${MESH:-60}" SOLVER="${SOLVER:-direct}" \
    LOAD_STEPS="${LOAD_STEPS:-}" python3 - <<'PY'
import collections, csv, json, math, os, random, subprocess
count, seed = int(os.environ["COUNT"]), int(os.environ["SEED"])
rng = random.Random(seed)
base = json.load(open("assets/scenes/specimen_single_flaw.json"))
rows, outcomes = [], collections.Counter()
print(f"{'scene':6s} {'flaws':>5s}  {'outcome':14s} {'steps':>5s} {'converged':>9s}  first growth")
for i in range(count):
    scene = json.loads(json.dumps(base))
    cracks = []
    for _ in range(rng.choice([1, 1, 1, 2, 2, 3])):
        length, deg = rng.uniform(0.002, 0.008), rng.uniform(-90.0, 90.0)
        cx, cy = rng.uniform(0.008, 0.022), rng.uniform(0.008, 0.022)
        dx, dy = 0.5 * length * math.cos(math.radians(deg)), 0.5 * length * math.sin(math.radians(deg))
        crack = {"points": [[cx - dx, cy - dy], [cx + dx, cy + dy]],
                 "friction": rng.choice([0.0, 0.2, 0.5, 0.8, 1.2])}
        if rng.random() < 0.3:
            crack["cohesion"] = rng.choice([2e6, 8e6, 15e6])
        cracks.append(crack)
    scene["cracks"], scene["name"] = cracks, f"random layout {i}"
    n = int(os.environ["MESH"])
    scene["mesh"], scene["solver"] = {"nx": n, "ny": n}, {"kind": os.environ["SOLVER"]}
    if os.environ["LOAD_STEPS"]:
        scene["growth"].update(control="load", load_steps=int(os.environ["LOAD_STEPS"]),
                               max_growth_per_step=20, max_steps=80)
        scene["boundary"]["top"]["normal"] = -150e6
    path = f"bench-out/random_layouts/r{i:02d}.json"
    json.dump(scene, open(path, "w"), indent=1)
    run = subprocess.run(["target/release/cdca", "grow", path], capture_output=True, text=True)
    if run.returncode == 2 or not run.stdout.strip():
        print(f"r{i:02d}   refused: {run.stderr.strip()}")
        outcomes["refused"] += 1
        continue
    report = json.loads(run.stdout)
    steps = report["steps"]
    converged = all(s["converged"] for s in steps)
    at = next((s for s in steps if s["grown"]), None)
    first = f"{at['grown'][0]['mode']} {abs(at['grown'][0]['angle_deg']):.1f}° at λ = {at['load_factor']:.3f}" if at else "none"
    outcomes[report["outcome"]] += 1
    print(f"r{i:02d}   {len(cracks):5d}  {report['outcome']:14s} {len(steps):5d} {str(converged):>9s}  {first}")
    rows.append([i, len(cracks), report["outcome"], len(steps), converged, first])
with open("bench-out/random_layouts.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["scene", "flaws", "outcome", "steps", "every_step_converged", "first_growth"])
    w.writerows(rows)
print("outcomes:", dict(outcomes), f"; every step converged in {sum(r[4] for r in rows)} of {len(rows)}")
PY
