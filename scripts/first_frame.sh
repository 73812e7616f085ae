#!/usr/bin/env bash
# The native workbench's first frame and first solved field, timed from
# process start over N starts (default 10) per scene, under a virtual
# display (Xvfb; Debian packages xvfb, libegl1, libegl-mesa0,
# libgl1-mesa-dri). Prints one row per scene: the median and the largest
# time to the first frame and to the field, and writes
# target/first_frame.csv. Run on an idle machine.
#
#   bash scripts/first_frame.sh [STARTS]
set -euo pipefail
cd "$(dirname "$0")/.."
starts="${1:-10}"
cargo build --release -p cdca-workbench --bin cdca-workbench >/dev/null
mkdir -p target/first_frame
python3 - <<'PY'
import json
base = json.load(open("assets/scenes/plate_45_biaxial_k0.2_mu0.5.json"))
for name, n, kind in [("plate_120_automaton", 120, "automaton"), ("plate_200_direct", 200, "direct")]:
    s = dict(base, name=name)
    s["mesh"] = dict(base["mesh"], nx=n, ny=n)
    s["solver"] = {"kind": kind}
    json.dump(s, open(f"target/first_frame/{name}.json", "w"))
PY
scenes=(assets/scenes/specimen_single_flaw.json
        target/first_frame/plate_120_automaton.json
        target/first_frame/plate_200_direct.json)
echo "scene,start,first_frame_s,field_s" > target/first_frame.csv
for scene in "${scenes[@]}"; do
    for i in $(seq "$starts"); do
        # a fresh settings folder: no earlier scene is restored
        home=$(mktemp -d)
        out=$(HOME="$home" XDG_DATA_HOME="$home" CDCA_STARTUP_REPORT=1 timeout 300 \
            xvfb-run -a -s "-screen 0 1400x900x24" \
            ./target/release/cdca-workbench "$scene" 2>&1 || true)
        rm -rf "$home"
        first=$(echo "$out" | sed -n 's/^startup: first frame \([0-9.]*\) s/\1/p' | head -1)
        field=$(echo "$out" | sed -n 's/^startup: field \([0-9.]*\) s/\1/p' | head -1)
        echo "$(basename "$scene" .json),$i,${first:-NA},${field:-NA}" >> target/first_frame.csv
    done
done
python3 - <<'PY'
import csv, statistics
rows = list(csv.DictReader(open("target/first_frame.csv")))
print(f"{'scene':<28}{'starts':>7}{'first frame median':>20}{'max':>8}{'field median':>14}{'max':>8}")
for scene in dict.fromkeys(r["scene"] for r in rows):
    r = [x for x in rows if x["scene"] == scene]
    f = [float(x["first_frame_s"]) for x in r if x["first_frame_s"] != "NA"]
    g = [float(x["field_s"]) for x in r if x["field_s"] != "NA"]
    med = lambda v: f"{statistics.median(v):.2f}" if v else "NA"
    mx = lambda v: f"{max(v):.2f}" if v else "NA"
    print(f"{scene:<28}{len(r):>7}{med(f):>20}{mx(f):>8}{med(g):>14}{mx(g):>8}")
PY
