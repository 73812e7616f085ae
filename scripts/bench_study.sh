#!/usr/bin/env bash
# `cdca study` on every core (docs/studies.md, *Speed-up*): POINTS points of
# even cost (the default specimen's flaw, STEPS growth steps, every point
# the same scene: the axis varies only the scene's description), run with
# `--jobs 1` and `--jobs 2` in turn, PAIRS times each (A B A B …), the
# solver's own threads off (`--solver-threads 1`; faer is single-threaded).
# Prints each run's wall time, the medians and the median of the pairs'
# ratios; then the overhead per run: the wall time of `--jobs 1` less the
# sum of its rows' `seconds`, and against POINTS `cdca grow` processes of
# the same scene. Run it on a quiet machine (uptime below 0.3). Leaves the
# study in bench-out/bench_study/even.json.
# Usage: [POINTS=8] [STEPS=8] [PAIRS=3] bash scripts/bench_study.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --workspace -q
POINTS=${POINTS:-8}
STEPS=${STEPS:-8}
PAIRS=${PAIRS:-3}
bin=$PWD/target/release/cdca
# the study stays (bench-out/ is not committed), for timing it by hand:
# each timed run starts from no table, or it would resume a finished one
dir=bench-out/bench_study
mkdir -p "$dir"
values=$(seq -s, 1 "$POINTS" | sed 's/\([0-9]*\)/"\1"/g')
cat >"$dir/even.json" <<EOF
{
  "name": "$POINTS points of even cost",
  "scene": "$PWD/assets/scenes/specimen_single_flaw.json",
  "set": { "growth.max_steps": $STEPS },
  "axes": [ { "field": "description", "values": [$values] } ]
}
EOF
uptime
now() { date +%s.%N; }
# one timed run: prints its wall seconds
timed() {
    rm -f "$dir/t.csv"
    local t0 t1
    t0=$(now)
    "$bin" study "$dir/even.json" --out "$dir/t.csv" --solver-threads 1 "$@" >/dev/null
    t1=$(now)
    echo "$t1 - $t0" | bc -l
}
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
one=() two=() ratio=()
for k in $(seq "$PAIRS"); do
    a=$(timed --jobs 1)
    b=$(timed --jobs 2)
    one+=("$a") two+=("$b") ratio+=("$(echo "$a / $b" | bc -l)")
    printf 'pair %d: --jobs 1 %.2f s, --jobs 2 %.2f s, speed-up %.3f\n' "$k" "$a" "$b" "${ratio[-1]}"
done
printf 'median: --jobs 1 %.2f s, --jobs 2 %.2f s; median speed-up %.3f\n' \
    "$(printf '%s\n' "${one[@]}" | median)" "$(printf '%s\n' "${two[@]}" | median)" \
    "$(printf '%s\n' "${ratio[@]}" | median)"

# overhead per run: the study's wall time against its rows' own seconds,
# and against a `cdca grow` process per point
wall=$(timed --jobs 1)
rows=$(awk -F, 'NR > 1 { s += $NF } END { print s }' "$dir/t.csv")
"$bin" study "$dir/even.json" --point 1 >"$dir/p.json"
t0=$(now)
for _ in $(seq "$POINTS"); do
    "$bin" grow "$dir/p.json" >/dev/null 2>&1 || true
done
t1=$(now)
grows=$(echo "$t1 - $t0" | bc -l)
printf 'overhead per run: %.1f ms (the study %.2f s less its rows %.2f s, over %d points)\n' \
    "$(echo "($wall - $rows) * 1000 / $POINTS" | bc -l)" "$wall" "$rows" "$POINTS"
printf 'a cdca grow process per point: %.2f s, %.1f ms a run against the study'"'"'s %.1f ms\n' \
    "$grows" "$(echo "$grows * 1000 / $POINTS" | bc -l)" "$(echo "$wall * 1000 / $POINTS" | bc -l)"
