#!/usr/bin/env bash
# Held-out flaw pairs (docs/fracture-model.md, "Coalescence"): 8 pairs of each
# layout (coplanar, stepped, overlapping) drawn at random, with a fixed seed,
# and the overlapping pairs once more with the second flaw reflected across
# the first flaw's line (the other step-over: "overlapping, mirrored"),
# and once more with the bridge at 120° to the horizontal, so that the
# flaws overlap across the load ("overlapping, across the load": Wong &
# Einstein's bridging angle above 90°),
# across the range of issue 34: flaws 3-4 mm long at 35-60° to the
# horizontal, face friction 0-0.6, a bridge between the facing tips of
# 0.7-1.3 flaw lengths; centred in the 30 mm specimen of the bundled pairs
# (100 × 100, product defaults: the contact a drawn crack gets, critical
# control), each grown to failure with `cdca grow`. Prints one row per run
# (outcome, steps, whether every step converged, secondary cracks, the
# first coalescence: step, λ_cr and what it joins), writes
# bench-out/pairs.csv, and the summary rows that `bash scripts/docs.sh`
# puts in docs/.
# Usage: [JOBS=2] bash scripts/held_out_pairs.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p cdca-cli
mkdir -p bench-out/pairs
JOBS="${JOBS:-2}" python3 - <<'PY'
import csv, json, math, os, random, subprocess
from concurrent.futures import ThreadPoolExecutor
base = json.load(open("assets/scenes/specimen_two_flaws_stepped.json"))
W = base["specimen"]["width"]

def unit(deg):
    return (math.cos(math.radians(deg)), math.sin(math.radians(deg)))

def pair(layout, length, deg, bridge):
    """The two flaws' end points (m), the pair centred in the specimen. The
    bridge runs from the first flaw's upper end to the second flaw's lower
    end: along the flaws (coplanar), up and slightly back, as in the bundled
    stepped pair (stepped), down across the flaws, as in the bundled
    overlapping pair until 2026-11-28 (overlapping: the second flaw on the side of the first
    that its faces' slip makes a restraining step-over), or that direction
    reflected across the first flaw's line (overlapping, mirrored: a
    releasing step-over), or up and back at 120° to the horizontal
    (overlapping, across the load)."""
    e = unit(deg)
    a0, a1 = (0.0, 0.0), (length * e[0], length * e[1])
    d = {"coplanar": e, "stepped": (-0.177, 0.984),
         "overlapping, across the load": unit(120)}.get(layout, (0.2, -0.98))
    if layout == "overlapping, mirrored":
        c, s = math.cos(2 * math.radians(deg)), math.sin(2 * math.radians(deg))
        d = (c * d[0] + s * d[1], s * d[0] - c * d[1])
    b0 = (a1[0] + bridge * d[0], a1[1] + bridge * d[1])
    b1 = (b0[0] + length * e[0], b0[1] + length * e[1])
    pts = [a0, a1, b0, b1]
    cx = 0.5 * (min(p[0] for p in pts) + max(p[0] for p in pts))
    cy = 0.5 * (min(p[1] for p in pts) + max(p[1] for p in pts))
    shift = lambda p: [0.5 * W + p[0] - cx, 0.5 * W + p[1] - cy]
    return [[shift(a0), shift(a1)], [shift(b0), shift(b1)]]

LAYOUTS = ("coplanar", "stepped", "overlapping", "overlapping, mirrored",
           "overlapping, across the load")
runs = []
for k, layout in enumerate(LAYOUTS):
    # the mirrored and across-the-load pairs are the overlapping draws
    rng = random.Random(34 + min(k, 2))
    for _ in range(8):
        length = rng.uniform(3e-3, 4e-3)
        runs.append((layout, length, rng.uniform(35, 60), round(rng.uniform(0, 0.6), 2),
                     rng.uniform(0.7, 1.3)))

def grow(run):
    layout, length, deg, mu, ratio = run
    scene = json.loads(json.dumps(base))
    scene["name"] = f"held-out {layout} pair"
    scene["cracks"] = [{"points": p, "friction": mu} for p in pair(layout, length, deg, ratio * length)]
    # to failure: the product's step cap (200), whatever the base scene says
    del scene["growth"]["max_steps"]
    path = f"bench-out/pairs/{layout.replace(', ', '_').replace(' ', '-')}_{length * 1e3:.2f}_{deg:.1f}_{mu}_{ratio:.2f}.json"
    json.dump(scene, open(path, "w"), indent=1)
    # exit 1 (a step that did not converge) still prints the history
    return json.loads(subprocess.run(["./target/release/cdca", "grow", path],
                                     capture_output=True, text=True).stdout)

with ThreadPoolExecutor(int(os.environ["JOBS"])) as pool:
    reports = list(pool.map(grow, runs))
rows = []
print(f"{'layout':21s} {'mm':>4s} {'angle':>5s} {'mu':>4s} {'bridge':>6s}  {'outcome':14s} {'steps':>5s} "
      f"{'converged':>9s} {'secondary':>9s}  first coalescence")
for (layout, length, deg, mu, ratio), report in zip(runs, reports):
    converged = all(s["converged"] for s in report["steps"])
    secondary = sum(len(s.get("started", [])) for s in report["steps"])
    c = report.get("coalescence")
    link = f"step {c['step']}, λ {c['load_factor']:.2f}, {c['category']}" if c else "-"
    rows.append([layout, f"{length * 1e3:.2f}", f"{deg:.1f}", mu, f"{ratio:.2f}", report["outcome"],
                 len(report["steps"]), converged, secondary, c["step"] if c else "",
                 f"{c['load_factor']:.3f}" if c else "", c["category"] if c else ""])
    print(f"{layout:21s} {length * 1e3:4.2f} {deg:5.1f} {mu:4.2f} {ratio:6.2f}  {report['outcome']:14s} "
          f"{len(report['steps']):5d} {str(converged):>9s} {secondary:9d}  {link}", flush=True)
with open("bench-out/pairs.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["layout", "flaw_mm", "angle_deg", "friction", "bridge_over_flaw", "outcome", "steps",
                "every_step_converged", "secondary_cracks", "coalescence_step", "coalescence_load_factor",
                "coalescence_category"])
    w.writerows(rows)
# the summary table of docs/fracture-model.md (*Coalescence*), between its
# markers through `bash scripts/docs.sh`
out = os.path.join(os.environ.get("CARGO_TARGET_DIR", "target"), "docs", "held-out-pairs")
os.makedirs(out, exist_ok=True)
for key, layout in enumerate(LAYOUTS):
    mine = [r for r in rows if r[0] == layout]
    firsts = sorted(r[9] for r in mine if r[9] != "")
    linked = f"{len(firsts)}"
    if firsts:
        linked += f" (steps {firsts[0]}–{firsts[-1]})" if firsts[0] != firsts[-1] else f" (step {firsts[0]})"
    kinds = {}
    for r in mine:
        if r[11]:
            kinds[r[11]] = kinds.get(r[11], 0) + 1
    how = ", ".join(f"{n} {k}" for k, n in sorted(kinds.items(), key=lambda x: (-x[1], x[0]))) or "–"
    outcomes = {}
    for r in mine:
        outcomes[r[5]] = outcomes.get(r[5], 0) + 1
    text = ", ".join(f"{n} {o}" for o, n in sorted(outcomes.items(), key=lambda x: (-x[1], x[0])))
    with open(os.path.join(out, f"{key + 1}-{layout.replace(', ', '-').replace(' ', '-')}.md"), "w") as f:
        f.write(f"| {layout} | {len(mine)} | {linked} | {how} | {sum(r[7] for r in mine)} | {text} |\n")
print(f"wrote bench-out/pairs.csv and {out}/")
PY
