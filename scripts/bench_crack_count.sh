#!/usr/bin/env bash
# Issue 61's table of a growth step's cost against the number of cracks
# the run has, at several meshes: at each mesh one held-out pair of
# assets/studies/held_out_pairs_rock.json grown to its end by `cdca grow`
# (by default the one whose run collects the most cracks at that mesh, from
# a run of all 40: point 32 at 60², 26 cracks; point 24 at 100², 57; point
# 23 at 200², 37; none reaches 40 at 60² or 200²); a step's crack
# count is the drawn cracks plus every crack started or branched before
# it (the largest crack index its report names, plus one). Per mesh and
# per count (2, 10, 20, 40) it prints the median cost of the steps within
# ±2 cracks of that count, in seconds and in cold solves (the median of 5
# wall times of `cdca solve` on the starting scene at that mesh), and the
# median contact and linear iterations of those steps. Writes
# bench-out/crack_count.csv (a row per step). A benchmark, not a test:
# times depend on the machine and its load.
# Usage: bash scripts/bench_crack_count.sh [CDCA_BIN] [MESH:POINT...]
#   (defaults: target/release/cdca, 60:32 100:24 200:23)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-target/release/cdca}
shift $(( $# < 1 ? $# : 1 ))
pairs=${*:-60:32 100:24 200:23}
[ -x "$bin" ] || cargo build --release -q -p cdca-cli
mkdir -p bench-out
python3 - "$bin" $pairs <<'PY'
import json, statistics, subprocess, sys, tempfile, time, os
binary = sys.argv[1]
pairs = [tuple(int(v) for v in p.split(":")) for p in sys.argv[2:]]
work = tempfile.mkdtemp(prefix="cdca-crack-count-")
study = "assets/studies/held_out_pairs_rock.json"

def wall(cmd):
    start = time.perf_counter()
    out = subprocess.run(cmd, capture_output=True, text=True).stdout
    return time.perf_counter() - start, out

def named(step):
    ids = [t["crack"] for t in step.get("tips", [])]
    ids += [n["crack"] for n in step.get("nucleated", [])]
    for l in step.get("links", []):
        ids += [l["crack"], l["main"]]
    return max(ids, default=-1) + 1

counts = [2, 10, 20, 40]
table, rows = [], []
for n, point in pairs:
    scene = json.loads(subprocess.run([binary, "study", study, "--point", str(point)],
                                      capture_output=True, text=True, check=True).stdout)
    drawn = len(scene["cracks"])
    scene["mesh"] = {"nx": n, "ny": n}
    path = os.path.join(work, f"point{point}_{n}.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    cold = statistics.median(wall([binary, "solve", path])[0] for _ in range(5))
    seconds, out = wall([binary, "grow", path])
    steps = json.loads(out)["steps"]
    cracks = drawn
    for s in steps:
        # the cracks this step solved with: those before it
        s["_cracks"] = cracks
        cracks = max(cracks, named(s))
        rows.append((n, point, s["step"], s["_cracks"], s["seconds"], s["seconds"] / cold,
                     s["work"]["contact_iterations"], s["work"]["linear_iterations"]))
    print(f"{n}², point {point}: {len(steps)} steps, {cracks} cracks at the end, {seconds:.1f} s, "
          f"cold solve {cold:.3f} s", file=sys.stderr, flush=True)
    cells = []
    for c in counts:
        near = [s for s in steps if abs(s["_cracks"] - c) <= 2]
        if not near:
            cells.append("—")
            continue
        sec = statistics.median(s["seconds"] for s in near)
        ci = statistics.median(s["work"]["contact_iterations"] for s in near)
        li = statistics.median(s["work"]["linear_iterations"] for s in near)
        cells.append(f"{sec:.3f} s = {sec / cold:.2f} ({ci:g} / {li:g})")
    table.append((n, point, cold, len(steps), cracks, cells))

print("| mesh | point | cold solve | steps, cracks at the end | " + " | ".join(f"{c} cracks" for c in counts) + " |")
print("| --- | --- | --- | --- | " + " | ".join("---" for _ in counts) + " |")
for n, point, cold, nsteps, cracks, cells in table:
    print(f"| {n}² | {point} | {cold:.3f} s | {nsteps}, {cracks} | " + " | ".join(cells) + " |")
print("\ncell: median step s = in cold solves (median contact / linear iterations); "
      "steps within ±2 cracks of the count")
with open("bench-out/crack_count.csv", "w") as f:
    f.write("mesh,point,step,cracks,seconds,cold_solves,contact_iterations,linear_iterations\n")
    for r in rows:
        f.write(",".join(str(v) for v in r) + "\n")
PY
