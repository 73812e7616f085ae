#!/usr/bin/env bash
# Runs every test of the workspace. Release mode: the solver's verification
# tests are heavy, and the optimised build runs them in a fraction of the time.
set -euo pipefail
cd "$(dirname "$0")/.."

cmd=(cargo test --workspace --release "$@")
echo "+ ${cmd[*]}"
"${cmd[@]}"
