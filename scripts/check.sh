#!/usr/bin/env bash
# What CI checks, runnable by anyone: formatting, no import cycles between
# the workbench's files, lints (warnings are errors), documentation, then the tests.
set -euo pipefail
cd "$(dirname "$0")/.."

run() {
    echo "+ $*"
    "$@"
}

run cargo fmt --all --check
run python3 scripts/import_cycles.py
run cargo clippy --workspace --all-targets -- -D warnings
RUSTDOCFLAGS="-D warnings" run cargo doc --workspace --no-deps
run bash scripts/test.sh
