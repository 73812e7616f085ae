#!/usr/bin/env bash
# Run growth in the workbench against `cdca grow` (issue 56, "No waiting"):
# on the three bundled two-flaw pairs, RUNS times each (default 3, in
# turn), the wall time of `cdca grow SCENE` and of the workbench's Run
# growth started from the command line (`cdca-workbench SCENE --run grow
# --time-run`, under Xvfb at 1400 × 900: from the frame the run starts in
# to the frame it ends in, the first solve excluded), the frames' CPU time
# (logic + UI; painting excluded) and interval meanwhile, the host's own
# time in the run (how much of it the host thread worked), and whether both
# grew the same steps to the same last λ. WORKBENCH=path/to/other/binary
# times another build (e.g. one from an earlier commit). A benchmark, not a
# test: times depend on the machine and its load.
#   RUNS=3 bash scripts/bench_workbench_growth.sh
set -euo pipefail
cd "$(dirname "$0")/.."
target="${CARGO_TARGET_DIR:-target}/release"
cargo build --release -q -p cdca-cli -p cdca-workbench
command -v xvfb-run >/dev/null || { echo "needs xvfb (apt-get install -y xvfb)"; exit 1; }
CDCA="$target/cdca" WORKBENCH="${WORKBENCH:-$target/cdca-workbench}" RUNS="${RUNS:-3}" python3 - <<'PY'
import json, os, re, subprocess, time

CDCA, WB, RUNS = os.environ["CDCA"], os.environ["WORKBENCH"], int(os.environ["RUNS"])
print(f"| pair | cdca grow, s | workbench Run growth, s | ratio | host's own time, s | frame CPU p95, ms | frame interval p95, ms | same steps and λ |")
print("| --- | --- | --- | --- | --- | --- | --- | --- |")
for pair in ["coplanar", "stepped", "overlapping"]:
    scene = f"assets/scenes/specimen_two_flaws_{pair}.json"
    cli, wb, host, p95, dt95, same = [], [], [], [], [], True
    for _ in range(RUNS):
        start = time.perf_counter()
        out = subprocess.run([CDCA, "grow", scene], capture_output=True, text=True).stdout
        cli.append(time.perf_counter() - start)
        steps = json.loads(out)["steps"]
        err = subprocess.run(
            ["xvfb-run", "-a", "-s", "-screen 0 1400x900x24", WB, scene, "--run", "grow", "--time-run"],
            capture_output=True, text=True, timeout=600).stderr
        m = re.search(r"run wall ([\d.]+) s; (\d+) growth steps, last λ (\S+); \d+ frames: CPU mean [\d.]+ ms, p95 ([\d.]+) ms.*interval mean [\d.]+ ms, p95 ([\d.]+) ms.*; host ([\d.]+) s", err)
        if not m:
            raise SystemExit(f"{pair}: no timing line from the workbench:\n{err[-2000:]}")
        wb.append(float(m[1])); p95.append(float(m[4])); dt95.append(float(m[5])); host.append(float(m[6]))
        same &= int(m[2]) == len(steps) and float(m[3]) == steps[-1]["load_factor"]
    r = lambda v: "–".join(f"{x:.1f}" for x in (min(v), max(v))) if len(v) > 1 else f"{v[0]:.1f}"
    ratio = [w / c for w, c in zip(wb, cli)]
    print(f"| {pair} | {r(cli)} | {r(wb)} | {r(ratio)} | {r(host)} | {r(p95)} | {r(dt95)} | {'yes' if same else 'NO'} |", flush=True)
PY
