#!/usr/bin/env bash
# The whole held-out flaw range of issue 17 grown to failure (docs/fracture-model.md, "The
# whole range, grown to failure"): a 3.5 mm closed flaw through the default
# specimen's centre (off the grid), at every angle β = 30–60° from the
# horizontal in steps of 5° and every face friction μ = 0–0.6 in steps of
# 0.1 at which the faces slide (τ > μσ_n), each grown to failure with
# `cdca grow` (product defaults; MESH sets the elements per side, default
# 60; LENGTH the flaw's length in mm, default 3.5). Prints one row per flaw: outcome, steps, whether every step
# converged, the first growth (mode, angle to the flaw), each wing's length
# in flaw lengths and the angle from the load axis of its last flaw length,
# the steps grown in shear, and the longest crack started at each flaw end
# (a secondary crack from the kink its wing left, with whatever grew from
# it); writes bench-out/flaw_range.csv (with
# another LENGTH, bench-out/flaw_range_<LENGTH>mm.csv).
# Its runs at the defaults are the study assets/studies/flaw_range.json
# (`cdca study`, docs/studies.md); this script stays for the wings'
# lengths and end angles, which a study's row does not hold.
# Usage: [MESH=100] [LENGTH=3] bash scripts/flaw_range.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p cdca-cli
mkdir -p bench-out/flaw_range
MESH="${MESH:-60}" LENGTH="${LENGTH:-3.5}" python3 - <<'PY'
import csv, json, math, os, subprocess
base = json.load(open("assets/scenes/specimen_single_flaw.json"))
n = int(os.environ["MESH"])
length_m, h = float(os.environ["LENGTH"]) / 1000.0, base["specimen"]["width"] / n
tag = "" if os.environ["LENGTH"] == "3.5" else f"_{os.environ['LENGTH']}mm"

def arc(p):
    return sum(math.dist(a, b) for a, b in zip(p, p[1:]))

def end_angle(p, over):
    """Angle from the vertical (°) of the chord over the last `over` of p."""
    k = len(p) - 1
    while k > 0 and math.dist(p[k], p[-1]) < over:
        k -= 1
    return abs(math.degrees(math.atan2(p[-1][0] - p[k][0], abs(p[-1][1] - p[k][1]))))

print(f"{'β':>3s} {'μ':>4s} {'τ−μσn':>6s}  {'outcome':10s} {'steps':>5s} {'conv':>5s}  first      wing 1 (L/flaw, end°)  wing 2   shear steps")
rows, misses, ends_reached = [], [], []
for deg in range(30, 61, 5):
    t = math.radians(deg)
    for mu in [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6]:
        drive = math.sin(t) * math.cos(t) - mu * math.cos(t) ** 2  # per unit load
        if drive <= 0.0:
            continue
        c = (0.015 + 0.37 * h, 0.015 + 0.21 * h)
        d = (0.5 * length_m * math.cos(t), 0.5 * length_m * math.sin(t))
        ends = [[c[0] - d[0], c[1] - d[1]], [c[0] + d[0], c[1] + d[1]]]
        scene = json.loads(json.dumps(base))
        scene["cracks"] = [{"points": ends, "friction": mu}]
        scene["mesh"] = {"nx": n, "ny": n}
        scene["name"] = f"{deg}° flaw, μ = {mu}"
        path = f"bench-out/flaw_range/b{deg}_mu{mu}{tag}.json"
        json.dump(scene, open(path, "w"), indent=1)
        run = subprocess.run(["target/release/cdca", "grow", path], capture_output=True, text=True)
        report = json.loads(run.stdout)
        steps = report["steps"]
        converged = all(s["converged"] for s in steps)
        grown = [g for s in steps for g in s["grown"]]
        first = grown[0] if grown else None
        poly = report["cracks"][0]
        at = sorted(min(range(len(poly)), key=lambda i: math.dist(poly[i], e)) for e in ends)
        wings = [poly[: at[0] + 1][::-1], poly[at[1]:]]
        wings = [(arc(w) / length_m, end_angle(w, length_m)) for w in wings]
        # a crack started at a flaw end (a secondary crack from the kink the
        # wing left) takes that end's growth on: the longest such crack per end
        started = [[c for c in report["cracks"][1:] if math.dist(c[0], e) < 1e-9] for e in ends]
        via = [max(((arc(c) / length_m, end_angle(c, length_m)) for c in cs), default=(0.0, 90.0))
               for cs in started]
        shear = sum(g["mode"] == "shear" for g in grown)
        first_text = f"{first['mode'][0].upper()} {abs(first['angle_deg']):4.1f}°" if first else "none"
        print(f"{deg:3d} {mu:4.1f} {drive:6.3f}  {report['outcome']:10s} {len(steps):5d} {str(converged):>5s}  {first_text:9s}  "
              f"{wings[0][0]:4.2f}, {wings[0][1]:4.1f}°           {wings[1][0]:4.2f}, {wings[1][1]:4.1f}°  {shear:3d}"
              f"   from the ends: {via[0][0]:4.2f}, {via[0][1]:4.1f}° / {via[1][0]:4.2f}, {via[1][1]:4.1f}°", flush=True)
        rows.append([deg, mu, round(drive, 3), report["outcome"], len(steps), converged, first_text,
                     round(wings[0][0], 2), round(wings[0][1], 1), round(wings[1][0], 2), round(wings[1][1], 1), shear,
                     round(via[0][0], 2), round(via[0][1], 1), round(via[1][0], 2), round(via[1][1], 1)])
        if not (converged and all(l >= 2.0 and e <= 15.0 for l, e in wings)):
            misses.append(f"{deg}°/{mu}")
        ends_reached.append(sum(any(l >= 2.0 and e <= 15.0 for l, e in pair) for pair in zip(wings, via)))
with open(f"bench-out/flaw_range{tag}.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["beta_deg", "mu", "drive_over_sigma", "outcome", "steps", "every_step_converged", "first_growth",
                "wing1_lengths", "wing1_end_deg", "wing2_lengths", "wing2_end_deg", "shear_steps",
                "from_end1_lengths", "from_end1_end_deg", "from_end2_lengths", "from_end2_end_deg"])
    w.writerows(rows)
lengths = [r[k] for r in rows for k in (7, 9)]
ends = [r[k] for r in rows for k in (8, 10)]
print(f"{len(rows)} flaws; every step converged in {sum(r[5] for r in rows)}; wings {min(lengths):.2f}–{max(lengths):.2f} "
      f"flaw lengths, ending {min(ends):.1f}–{max(ends):.1f}° from the load axis; "
      f"short of 2 flaw lengths, beyond 15° or unconverged: {misses or 'none'}")
wing_ends = sum(l >= 2.0 and e <= 15.0 for r in rows for l, e in ((r[7], r[8]), (r[9], r[10])))
print(f"flaw ends whose wing reaches 2 flaw lengths within 15° of the load axis: {wing_ends} of {2 * len(rows)}; "
      f"whose wing or a crack started at that end does: {sum(ends_reached)} of {2 * len(rows)}")
PY
