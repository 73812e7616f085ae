#!/usr/bin/env bash
# Would branching link the coplanar pair? (docs/fracture-model.md, "Coalescence"): the
# bundled coplanar pair grown STEPS growth steps (default 6, λ_cr = 1.54,
# where the faces' shear check around the inner flaw ends reaches 1), then
# a branch of one increment (1.34 mm) drawn into the bridge from the lower
# flaw's inner end, then from both inner ends, at each angle of ANGLES
# (degrees counter-clockwise off the flaw plane, default "-18 0 18"), and
# the whole grown on to failure with `cdca grow` (product defaults).
# Prints, per case, how each branch tip first grows, the steps at which a
# grown tip ended on another crack (a link), where each branch ends, and
# the outcome; writes bench-out/bridge_branch.csv.
# Usage: [STEPS=6] [ANGLES="-18 0 18"] bash scripts/bridge_branch.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p cdca-cli
mkdir -p bench-out/bridge_branch
STEPS="${STEPS:-6}" ANGLES="${ANGLES:--18 0 18}" python3 - <<'PY'
import csv, json, math, os, subprocess, sys
sys.path.insert(0, "scripts")
from polyline import on_polyline
steps, angles = int(os.environ["STEPS"]), [float(a) for a in os.environ["ANGLES"].split()]
base = json.load(open("assets/scenes/specimen_two_flaws_coplanar.json"))
work = "bench-out/bridge_branch"

def grow(scene, name):
    path = f"{work}/{name}.json"
    json.dump(scene, open(path, "w"), indent=1)
    # exit 1 (a step that did not converge) still prints the history
    return json.loads(subprocess.run(["./target/release/cdca", "grow", path],
                                     capture_output=True, text=True).stdout)

lower, upper = (c["points"] for c in base["cracks"])
mu = base["cracks"][0]["friction"]
head = dict(base, growth=dict(base["growth"], max_steps=steps))
grown = grow(head, "head")
print(f"coplanar pair after {steps} steps: λ_cr = {grown['steps'][-1]['load_factor']:.3f}")
# the inner ends: the lower flaw's upper end and the upper flaw's lower end
ends = [(lower[1], math.atan2(lower[1][1] - lower[0][1], lower[1][0] - lower[0][0])),
        (upper[0], math.atan2(upper[0][1] - upper[1][1], upper[0][0] - upper[1][0]))]
length = 1.34e-3
rows = []
print(f"{'branches':>8s} {'angle':>6s}  {'first growth of the branches':44s} {'link steps':>10s}  {'branch ends (mm)':28s} outcome")
for count, off in ((n, a) for n in (1, 2) for a in angles):
    cracks = [{"points": c, "friction": mu} for c in grown["cracks"]]
    for (x, y), along in ends[:count]:
        a = along + math.radians(off)
        cracks.append({"points": [[x, y], [x + length * math.cos(a), y + length * math.sin(a)]],
                       "friction": mu})
    scene = dict(base, cracks=cracks)
    report = grow(scene, f"branch_{count}_{off:+.0f}")
    branches = range(len(cracks) - count, len(cracks))
    first = []
    for b in branches:
        hit = next(((s, g) for s in report["steps"] for g in s["grown"] if g["crack"] == b), None)
        first.append(f"{hit[1]['mode']} {hit[1]['angle_deg']:.1f}° (λ {hit[0]['load_factor']:.2f})"
                     if hit else "none")
    links = sorted({s["step"] for s in report["steps"] for g in s["grown"]
                    if any(k != g["crack"] and on_polyline((g["x"], g["y"]), c)
                           for k, c in enumerate(report["cracks"]))})
    tips = [report["cracks"][b][-1] for b in branches]
    end = "  ".join(f"({p[0] * 1e3:.2f}, {p[1] * 1e3:.2f})" for p in tips)
    print(f"{count:8d} {off:+6.0f}  {' / '.join(first):44s} {' '.join(map(str, links)) or '-':>10s}  {end:28s} "
          f"{report['outcome']} after {len(report['steps'])}", flush=True)
    rows.append([count, off, " / ".join(first), " ".join(map(str, links)), end, report["outcome"],
                 len(report["steps"])])
with open("bench-out/bridge_branch.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["branches", "angle_off_flaw_deg", "first_growth", "link_steps", "branch_ends_mm", "outcome", "steps"])
    w.writerows(rows)
PY
