#!/usr/bin/env bash
# Runs every test of the workspace. Release mode: the solver's verification
# tests are heavy, and the optimised build runs them in a fraction of the time.
# The tests that measure a table of docs/ write its rows to target/docs/
# (docs/README.md); the rows of an earlier run are removed first, so that
# `bash scripts/docs.sh --check` sees only what this run measured.
set -euo pipefail
cd "$(dirname "$0")/.."

rm -rf "${CARGO_TARGET_DIR:-target}/docs"
cmd=(cargo test --workspace --release "$@")
echo "+ ${cmd[*]}"
"${cmd[@]}"
