#!/usr/bin/env bash
# What CI checks, runnable by anyone: formatting, lints (warnings are
# errors), documentation, then the tests (among them the import-cycle checks
# of the solver crate and the workbench, crates/cdca/tests/layout.rs and
# tests/layout.rs), then that the measured tables in docs/ are the ones the
# tests measured (scripts/docs.sh --check).
set -euo pipefail
cd "$(dirname "$0")/.."

run() {
    echo "+ $*"
    "$@"
}

run cargo fmt --all --check
run cargo clippy --workspace --all-targets -- -D warnings
RUSTDOCFLAGS="-D warnings" run cargo doc --workspace --no-deps
run bash scripts/test.sh
run bash scripts/docs.sh --check
