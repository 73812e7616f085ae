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
# during `bash scripts/test.sh`) and the slow studies (held_out_study below).
# The table of ignored tests is read from the sources here.
#
# Usage:
#   bash scripts/docs.sh           the quick tables, then the slow ones
#                                  (runs assets/studies/held_out_pairs.json
#                                  with `cdca study`, 2 min on 2 cores)
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
slow=(held-out-pairs)

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

# The held-out pairs' table (docs/fracture-model.md, *Coalescence*): the
# study assets/studies/held_out_pairs.json, run afresh (its table's rows
# are the code's of the day: a table left from other code is not resumed),
# and the summary per layout that `cdca study` prints, one row file each.
held_out_study() {
    cargo build --release --workspace -q
    mkdir -p bench-out
    local out=$rows/held-out-pairs
    rm -rf "$out"
    mkdir -p "$out"
    rm -f bench-out/held_out_pairs.csv
    "$target/release/cdca" study assets/studies/held_out_pairs.json \
        --out bench-out/held_out_pairs.csv |
        awk -v dir="$out" '/^\| / && !/^\| (layout|---) / { n++; print > sprintf("%s/%02d.md", dir, n) }'
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
    held_out_study
    generate docs "${slow[@]}"
    ;;
esac
