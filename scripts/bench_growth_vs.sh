#!/usr/bin/env bash
# Growth cost against another build (issue 35): `cdca grow` on the bundled
# two-flaw specimens, the single flaw and two held-out pairs (100 × 100 but
# the single flaw's 60 × 60, product defaults), this build against a
# BASELINE build of `cdca` (e.g. one built from an earlier commit in a git
# worktree), run in turn (A B A B ..., medians of RUNS each); prints steps,
# seconds, ms per step, the ratio, the cost of a step in cold `cdca solve`s
# of the same scene, and whether the two builds grew the same cracks
# (largest relative difference of λ_cr over the steps, of crack points in
# m, and the same modes, steps and outcome). `--scaling` instead times the
# first STEPS steps of the single flaw and the coplanar pair at 60², 100²,
# 200² and 300² (this build, and BASELINE if given). Writes
# bench-out/growth_vs.csv or bench-out/growth_scaling.csv. A benchmark, not
# a test: times depend on the machine and its load.
# Usage: BASELINE=path/to/old/cdca RUNS=3 bash scripts/bench_growth_vs.sh
#        BASELINE=... STEPS=8 bash scripts/bench_growth_vs.sh --scaling
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p cdca-cli
mkdir -p bench-out/growth_vs
python3 - "$@" <<'PY'
import json, math, os, statistics, subprocess, sys, time

NEW = "./target/release/cdca"
BASE = os.environ.get("BASELINE")
RUNS = int(os.environ.get("RUNS", "3"))

def run(binary, verb, path):
    start = time.perf_counter()
    out = subprocess.run([binary, verb, path], capture_output=True, text=True).stdout
    return time.perf_counter() - start, json.loads(out)

def flaw(cx, cy, deg, mu, length=0.003):
    a = math.radians(deg)
    dx, dy = 0.5 * length * math.cos(a), 0.5 * length * math.sin(a)
    return {"points": [[cx - dx, cy - dy], [cx + dx, cy + dy]], "friction": mu}

def held_out(layout, dx, dy, deg, mu):
    scene = json.load(open("assets/scenes/specimen_two_flaws_stepped.json"))
    scene["name"] = f"held-out {layout} pair"
    scene["cracks"] = [flaw(0.015 - dx / 2e3, 0.015 - dy / 2e3, deg, mu),
                       flaw(0.015 + dx / 2e3, 0.015 + dy / 2e3, deg, mu)]
    path = f"bench-out/growth_vs/{layout}_{dx}_{dy}_{deg}_{mu}.json"
    json.dump(scene, open(path, "w"), indent=1)
    return path

def with_mesh(path, n, steps):
    scene = json.load(open(path))
    scene["mesh"] = {"nx": n, "ny": n}
    scene["growth"]["max_steps"] = steps
    out = f"bench-out/growth_vs/{os.path.basename(path)[:-5]}_{n}.json"
    json.dump(scene, open(out, "w"), indent=1)
    return out

def same(a, b):
    lam = max((abs(x["load_factor"] - y["load_factor"]) / abs(y["load_factor"])
               for x, y in zip(a["steps"], b["steps"])), default=0.0)
    pts = max((max(abs(p[0] - q[0]), abs(p[1] - q[1]))
               for ca, cb in zip(a["cracks"], b["cracks"]) for p, q in zip(ca, cb)), default=0.0)
    modes = [[g["mode"] for g in s["grown"]] for s in a["steps"]] == \
            [[g["mode"] for g in s["grown"]] for s in b["steps"]]
    shape = len(a["steps"]) == len(b["steps"]) and [len(c) for c in a["cracks"]] == [len(c) for c in b["cracks"]]
    return lam, pts, modes and shape and a["outcome"] == b["outcome"]

if "--scaling" in sys.argv[1:]:
    steps = int(os.environ.get("STEPS", "8"))
    head = ("scene", "mesh", "steps", "before ms/step", "after ms/step", "after / before",
            "cold solve ms", "step / cold")
    rows = []
    for scene in ["assets/scenes/specimen_single_flaw.json", "assets/scenes/specimen_two_flaws_coplanar.json"]:
        for n in [60, 100, 200, 300]:
            path = with_mesh(scene, n, steps)
            wall, rep = run(NEW, "grow", path)
            before = run(BASE, "grow", path)[0] if BASE else float("nan")
            cold = statistics.median(run(NEW, "solve", path)[0] for _ in range(RUNS))
            k = max(len(rep["steps"]), 1)
            rows.append((os.path.basename(scene)[:-5], f"{n}²", k, f"{1e3 * before / k:.0f}",
                         f"{1e3 * wall / k:.0f}", f"{wall / before:.2f}", f"{1e3 * cold:.0f}",
                         f"{wall / k / cold:.2f}"))
            print(rows[-1], flush=True)
    out = "bench-out/growth_scaling.csv"
else:
    scenes = [f"assets/scenes/specimen_two_flaws_{s}.json" for s in ("coplanar", "stepped", "overlapping")]
    scenes += ["assets/scenes/specimen_single_flaw.json",
               held_out("stepped", 1.0, 5, 45, 0.5), held_out("overlapping", 2.4, -1.2, 45, 0.5)]
    head = ("scene", "steps", "before s", "after s", "after / before", "ms/step", "cold solve ms",
            "step / cold", "max Δλ_cr (rel.)", "max Δ point (m)", "same modes")
    rows = []
    for path in scenes:
        new_t, old_t = [], []
        for _ in range(RUNS):
            t, rep = run(NEW, "grow", path)
            new_t.append(t)
            if BASE:
                t, old = run(BASE, "grow", path)
                old_t.append(t)
        cold = statistics.median(run(NEW, "solve", path)[0] for _ in range(RUNS))
        after = statistics.median(new_t)
        before = statistics.median(old_t) if BASE else float("nan")
        k = max(len(rep["steps"]), 1)
        lam, pts, modes = same(rep, old) if BASE else (float("nan"), float("nan"), "-")
        rows.append((os.path.basename(path)[:-5], k, f"{before:.2f}", f"{after:.2f}",
                     f"{after / before:.2f}", f"{1e3 * after / k:.0f}", f"{1e3 * cold:.0f}",
                     f"{after / k / cold:.2f}", f"{lam:.1e}", f"{pts:.1e}", modes))
        print(rows[-1], flush=True)
    out = "bench-out/growth_vs.csv"
print("| " + " | ".join(head) + " |")
print("|" + " --- |" * len(head))
for r in rows:
    print("| " + " | ".join(map(str, r)) + " |")
with open(out, "w") as f:
    f.write(",".join(h.replace(" ", "_").replace("/", "per") for h in head) + "\n")
    for r in rows:
        f.write(",".join(map(str, r)) + "\n")
print(f"wrote {out}")
PY
