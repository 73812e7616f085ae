#!/usr/bin/env bash
# The field at the kink vertices of the bundled coplanar pair (docs/fracture-model.md,
# "Coalescence"): the pair grown STEPS growth steps (default 3: by then a
# wing has left three or four of the flaws' ends) on each mesh of MESHES
# (default "100 150 200 300" elements per side), then the criterion's
# tension and shear checks on circles of RADII mm (default "0.3 0.6 1.2")
# around each flaw end (example `kink_vertex`). Prints, per mesh and radius,
# the range over the ends that have become vertices of the shear check and
# of its angle off the flaw; writes every row to bench-out/kink_vertex.csv.
# Usage: [MESHES="100 200"] [STEPS=3] [RADII="0.3 0.6"] bash scripts/kink_vertex.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p cdca --example kink_vertex
mkdir -p bench-out/kink_vertex
meshes="${MESHES:-100 150 200 300}"
steps="${STEPS:-3}"
read -r -a radii <<< "${RADII:-0.3 0.6 1.2}"
out=bench-out/kink_vertex.csv
rm -f "$out"
for n in $meshes; do
    scene="bench-out/kink_vertex/coplanar_$n.json"
    python3 - "$n" "$scene" <<'PY'
import json, sys
s = json.load(open("assets/scenes/specimen_two_flaws_coplanar.json"))
s["mesh"] = {"nx": int(sys.argv[1]), "ny": int(sys.argv[1])}
json.dump(s, open(sys.argv[2], "w"), indent=1)
PY
    rows=$(target/release/examples/kink_vertex "$scene" "$steps" "${radii[@]}")
    if [[ -f "$out" ]]; then tail -n +2 <<< "$rows" >> "$out"; else echo "$rows" > "$out"; fi
done
python3 - "$out" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print(f"{'mesh':>5s} {'λ':>7s} {'vertices':>8s} {'r (mm)':>6s}  {'shear check':>12s}  {'angle off the flaw':>18s}")
for mesh in dict.fromkeys(r["mesh"] for r in rows):
    for radius in dict.fromkeys(r["r_mm"] for r in rows):
        v = [r for r in rows if r["mesh"] == mesh and r["r_mm"] == radius and r["free_tip"] == "false"]
        if not v:
            continue
        s = [float(r["shear"]) for r in v]
        a = [abs(float(r["shear_deg"])) for r in v]
        print(f"{mesh:>5s} {float(v[0]['load_factor']):7.3f} {len(v):8d} {float(radius):6.2f}  "
              f"{min(s):5.2f}–{max(s):5.2f}  {min(a):8.1f}–{max(a):4.1f}°")
PY
