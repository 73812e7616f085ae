#!/usr/bin/env bash
# Issue 61's yardstick: the 40 held-out pairs of
# assets/studies/held_out_pairs_rock.json grown to their end by two `cdca`
# binaries side by side (A, then B, point by point, on one machine), each
# point's step costs in cold solves: the median of 5 wall times of
# `cdca solve` on the point's starting scene, measured beside the run.
# Prints per binary: total time, the mean step pooled over all runs (the
# sum of run times over the sum, per run, of its steps times its cold
# solve), the slowest step in cold solves, contact iterations per step
# summed over the λ_cr trials (p95 and max; a binary whose reports lack
# `work` prints -), every step converged; then the points whose peak λ
# moved by more than 1% or whose first link changed. Writes
# bench-out/held_out_<label>.csv, a row per point. A benchmark, not a
# test: times depend on the machine and its load.
# Usage: bash scripts/bench_held_out.sh A_BIN B_BIN [POINTS]
#   (POINTS: how many of the 40, default all; A is "before", B "after")
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 2 ] || { echo "usage: bash scripts/bench_held_out.sh A_BIN B_BIN [POINTS]" >&2; exit 2; }
mkdir -p bench-out
python3 - "$@" <<'PY'
import json, os, statistics, subprocess, sys, tempfile, time
a_bin, b_bin = sys.argv[1], sys.argv[2]
points = int(sys.argv[3]) if len(sys.argv) > 3 else 40
study = "assets/studies/held_out_pairs_rock.json"
work = tempfile.mkdtemp(prefix="cdca-held-out-")

def wall(cmd):
    start = time.perf_counter()
    out = subprocess.run(cmd, capture_output=True, text=True).stdout
    return time.perf_counter() - start, out

rows = {"A": [], "B": []}
for k in range(1, points + 1):
    scene = os.path.join(work, f"point{k}.json")
    with open(scene, "w") as f:
        f.write(subprocess.run([b_bin, "study", study, "--point", str(k)],
                               capture_output=True, text=True, check=True).stdout)
    for label, binary in (("A", a_bin), ("B", b_bin)):
        cold = statistics.median(wall([binary, "solve", scene])[0] for _ in range(5))
        seconds, out = wall([binary, "grow", scene])
        run = json.loads(out)
        steps = run["steps"]
        iters = [s["work"]["contact_iterations"] for s in steps if "work" in s]
        link = next((l for s in steps for l in s.get("links", []) if l.get("coalescence")), None)
        rows[label].append(dict(
            point=k, cold=cold, seconds=seconds, steps=len(steps),
            slowest=max((s["seconds"] for s in steps), default=0.0) / cold,
            iters=iters if len(iters) == len(steps) else None,
            converged=all(s["converged"] for s in steps), outcome=run["outcome"],
            peak=max((s["load_factor"] for s in steps), default=0.0),
            link=None if link is None else "-".join(link["joins"])))
    print(f"point {k}: A {rows['A'][-1]['seconds']:.2f} s, B {rows['B'][-1]['seconds']:.2f} s",
          file=sys.stderr, flush=True)

def pct(v, q):
    v = sorted(v)
    return v[min(len(v) - 1, int(q * len(v)))]

print("| binary | total s | mean step (cold solves) | slowest step (cold solves) | contact iterations per step p95 / max | every step converged |")
print("| --- | --- | --- | --- | --- | --- |")
for label, binary in (("A", a_bin), ("B", b_bin)):
    r = rows[label]
    total = sum(x["seconds"] for x in r)
    mean = total / sum(x["steps"] * x["cold"] for x in r)
    slowest = max(x["slowest"] for x in r)
    iters = [i for x in r if x["iters"] is not None for i in x["iters"]]
    it = f"{pct(iters, 0.95)} / {max(iters)}" if iters and all(x["iters"] is not None for x in r) else "-"
    conv = sum(x["converged"] for x in r)
    print(f"| {label}: {binary} | {total:.1f} | {mean:.2f} | {slowest:.1f} | {it} | {conv} of {len(r)} |")
    with open(f"bench-out/held_out_{label}.csv", "w") as f:
        f.write("point,cold_s,seconds,steps,slowest_step_cold_solves,max_contact_iterations,converged,outcome,peak_load_factor,first_link\n")
        for x in r:
            f.write(f"{x['point']},{x['cold']:.4f},{x['seconds']:.3f},{x['steps']},{x['slowest']:.2f},"
                    f"{max(x['iters']) if x['iters'] else ''},{x['converged']},{x['outcome']},{x['peak']:.10g},{x['link'] or ''}\n")
ratio = sum(x["seconds"] for x in rows["A"]) / sum(x["seconds"] for x in rows["B"])
print(f"\ntotal time A/B: {ratio:.2f}")
moved = [(a["point"], a["peak"], b["peak"], a["link"], b["link"]) for a, b in zip(rows["A"], rows["B"])
         if abs(b["peak"] - a["peak"]) > 0.01 * a["peak"] or a["link"] != b["link"]]
print(f"same answers (peak λ within 1%, same first link): {len(rows['A']) - len(moved)} of {len(rows['A'])}")
for p in moved:
    print(f"  point {p[0]}: peak λ {p[1]:.5f} → {p[2]:.5f}, first link {p[3]} → {p[4]}")
PY
