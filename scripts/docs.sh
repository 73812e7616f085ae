#!/usr/bin/env bash
# Regenerates the measured tables in docs/ (see docs/README.md).
#
# Every measured table sits between two markers,
#     <!-- generated:NAME -->
#     | header |          <- the two lines after the start marker are kept
#     | --- |
#     | rows … |          <- replaced by the rows in target/docs/NAME/*.md
#     <!-- end:NAME -->
# The rows are written by whatever measures them, one file per row, sorted
# by file name: the tests (through crates/cdca/tests/support/docs_row.rs,
# during `bash scripts/test.sh`) and the slow studies (study_tables and
# flaw_strength_table below).
# The table of ignored tests is read from the sources here.
#
# Usage:
#   bash scripts/docs.sh           the quick tables, then the slow ones
#                                  (runs the studies held_out_pairs.json,
#                                  held_out_pairs_rock.json and
#                                  flaw_strength.json with `cdca study`,
#                                  about 8 min on 2 cores)
#   bash scripts/docs.sh --quick   the quick tables: the rows the last
#                                  `bash scripts/test.sh` wrote, and the
#                                  ignored tests (runs the tests if no rows
#                                  are there yet)
#   bash scripts/docs.sh --check   the quick tables into a temporary copy of
#                                  docs/; fails with the diff if docs/ says
#                                  something else (CI, after the tests)
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:-all}
case "$mode" in
all | --quick | --check) ;;
*)
    echo "usage: bash scripts/docs.sh [--quick | --check]" >&2
    exit 2
    ;;
esac

target=${CARGO_TARGET_DIR:-target}
rows=$target/docs
quick=(verification transitions flaw-range-first-growth ignored-tests)
slow=(held-out-pairs held-out-pairs-kinds held-out-pairs-rock held-out-pairs-rock-kinds flaw-strength)

# The tests that are #[ignore]d, with the reason they give: one row each in
# $rows/ignored-tests/.
ignored_tests() {
    rm -rf "$rows/ignored-tests"
    mkdir -p "$rows/ignored-tests"
    local f
    for f in crates/*/tests/*.rs tests/*.rs; do
        awk -v file="$f" -v out="$rows/ignored-tests" '
            /#\[ignore/ {
                reason = $0
                sub(/.*#\[ignore *(= *")?/, "", reason)
                sub(/"?\].*/, "", reason)
                pending = 1
                next
            }
            pending && /fn [a-z_0-9]+/ {
                name = $0
                sub(/.*fn /, "", name)
                sub(/\(.*/, "", name)
                stem = file
                sub(/\.rs$/, "", stem)
                gsub(/\//, "-", stem)
                printf "| `%s` | `%s` | %s |\n", name, file, reason > (out "/" stem "-" name ".md")
                pending = 0
            }
        ' "$f"
    done
}

# A study's tables (docs/fracture-model.md): the study STUDY run afresh
# (its table's rows are the code's of the day: a table left from other
# code is not resumed), and the summaries `cdca study` prints, one row file
# each: the first table's rows under NAME, the second's (the first links by
# the kinds of crack that made them) under NAME-kinds.
study_tables() {
    local study=$1 name=$2
    cargo build --release --workspace -q
    mkdir -p bench-out
    rm -rf "$rows/$name" "$rows/$name-kinds"
    mkdir -p "$rows/$name" "$rows/$name-kinds"
    rm -f "bench-out/$name.csv"
    "$target/release/cdca" study "$study" --out "bench-out/$name.csv" |
        awk -v a="$rows/$name" -v b="$rows/$name-kinds" '
            /^\| layout / { table++ }
            /^\| / && !/^\| (layout|---) / {
                n++
                print > sprintf("%s/%02d.md", (table == 1 ? a : b), n)
            }'
}

# The single-flaw strength table (docs/fracture-model.md, *The intact
# rock*): the study assets/studies/flaw_strength.json run afresh, and per
# flaw angle and face friction the peak over the uncracked specimen's
# strength for each flaw length, and whether it falls as the flaw
# lengthens.
flaw_strength_table() {
    study_tables assets/studies/flaw_strength.json flaw-strength-runs
    rm -rf "$rows/flaw-strength"
    mkdir -p "$rows/flaw-strength"
    python3 - "bench-out/flaw-strength-runs.csv" "$rows/flaw-strength" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
lengths = sorted({float(r["flaws.length"]) for r in rows})
for deg in sorted({float(r["flaws.angle_deg"]) for r in rows}):
    for mu in sorted({float(r["flaws.friction"]) for r in rows}):
        mine = {float(r["flaws.length"]): r for r in rows
                if float(r["flaws.angle_deg"]) == deg and float(r["flaws.friction"]) == mu}
        ratios = [float(mine[l]["strength_ratio"]) for l in lengths]
        falls = all(b < a for a, b in zip(ratios, ratios[1:]))
        cells = [f"{deg:g}°", f"{mu:g}"] + [f"{x:.3f}" for x in ratios] + \
                [f"{max(ratios):.3f}", "yes" if falls else "no"]
        open(f"{sys.argv[2]}/{deg:03.0f}-{mu:.1f}.md", "w").write("| " + " | ".join(cells) + " |\n")
PY
}

# splice FILE NAME: the rows of table NAME put between its markers in FILE.
splice() {
    local file=$1 name=$2 tmp
    tmp=$(mktemp)
    # sorted by file name, in the C locale, so that every machine agrees
    LC_ALL=C find "$rows/$name" -maxdepth 1 -name '*.md' | LC_ALL=C sort | xargs -r cat >"$tmp.rows"
    awk -v name="$name" -v rows="$tmp.rows" '
        $0 == "<!-- generated:" name " -->" { print; inside = 1; kept = 0; next }
        inside && $0 == "<!-- end:" name " -->" {
            while ((getline line < rows) > 0) print line
            close(rows)
            print
            inside = 0
            next
        }
        inside { if (kept < 2) { print; kept++ } next }
        { print }
    ' "$file" >"$tmp"
    mv "$tmp" "$file"
    rm -f "$tmp.rows"
}

# generate DIR NAME…: every table NAME in the Markdown files under DIR.
generate() {
    local dir=$1 name file
    shift
    for name in "$@"; do
        if [ ! -d "$rows/$name" ] || [ -z "$(ls -A "$rows/$name")" ]; then
            echo "docs.sh: no rows for table '$name' in $rows/$name (run bash scripts/test.sh first)" >&2
            exit 1
        fi
        local found=0
        for file in "$dir"/*.md; do
            if grep -qx "<!-- generated:$name -->" "$file"; then
                splice "$file" "$name"
                found=1
            fi
        done
        if [ "$found" = 0 ]; then
            echo "docs.sh: no file in $dir has the markers of table '$name'" >&2
            exit 1
        fi
    done
}

if [ ! -d "$rows/verification" ]; then
    echo "+ bash scripts/test.sh (no rows in $rows yet)"
    bash scripts/test.sh
fi
ignored_tests

case "$mode" in
--check)
    copy=$(mktemp -d)
    trap 'rm -rf "$copy"' EXIT
    cp docs/*.md "$copy"/
    generate "$copy" "${quick[@]}"
    if ! diff -u docs "$copy"; then
        echo "docs.sh: docs/ differs from what the tests measured (above);" \
            "run bash scripts/docs.sh --quick and commit the result" >&2
        exit 1
    fi
    echo "docs.sh: the quick tables in docs/ match the measurements"
    ;;
--quick)
    generate docs "${quick[@]}"
    ;;
all)
    generate docs "${quick[@]}"
    study_tables assets/studies/held_out_pairs.json held-out-pairs
    study_tables assets/studies/held_out_pairs_rock.json held-out-pairs-rock
    flaw_strength_table
    generate docs "${slow[@]}"
    ;;
esac
