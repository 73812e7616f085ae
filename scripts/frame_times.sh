#!/usr/bin/env bash
# Frame times of the workbench during Run growth on the default scene,
# natively (logic + UI on the CPU through egui_kittest, no GPU): prints the
# per-frame times and the mean, p95 and worst frame. Run on an idle machine.
#
#   bash scripts/frame_times.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --release -p cdca-workbench --test ui frame_time_during_run_growth \
    -- --include-ignored --nocapture 2>&1 | grep -E "frame|test result"
