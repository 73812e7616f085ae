#!/usr/bin/env bash
# Browser test of the WebAssembly build: builds dist/ (scripts/build-web.sh),
# serves it on 127.0.0.1, opens it in headless Chromium (Debian's chromium,
# driven by playwright-core from npm; no browser download), waits for the
# canvas and the solved default scene, clicks Step and "Grow one step",
# saves a screenshot and fails on any console error or panic message
# (tests/web/smoke.mjs). Then, in a fresh page, it presses Run growth on the
# bundled stepped pair and prints the run's time and the browser's frame
# times until it ends ("browser frame times during Run growth: ...";
# CDCA_RUN_GROWTH_MS caps the duration, default 60 s, 0 skips it): once
# with the solver on the page (?cdca_no_worker, the fallback) and once on
# its Web Worker, which must grow the same steps at the same λ as each
# other and as `cdca grow` (when target/release/cdca is built). Last,
# the layout at 1280 × 800, 1024 × 640 and 390 × 844, loaded and resized,
# and after Run growth (tests/web/layout.mjs, screenshots web-layout-*.png
# next to SCREENSHOT); and a link copied after a run, which opens the scene
# as drawn, taken out of the address by Reset (tests/web/link.mjs).
#
#   bash scripts/test-web.sh [--no-build | --rustup] [--first-frame [STARTS] [--old DIR]] [SCREENSHOT]
#       SCREENSHOT defaults to target-web/web-screenshot.png; the app's
#       solve and frame timings, and the Run growth frame times, go next
#       to it (web-timings.txt). --rustup builds with rustup's wasm target
#       (scripts/build-web.sh --rustup). --first-frame: instead of the
#       tests, times the first frame and the first field over STARTS
#       starts (default 10) per scene (tests/web/first_frame.mjs; writes
#       web-first-frame.csv next to SCREENSHOT); with --old DIR, the
#       bundle in DIR (an older dist/) too, their starts alternated. Run on
#       an idle machine.
#
# Installs what it needs: chromium (apt-get), playwright-core (npm ci).
set -euo pipefail
cd "$(dirname "$0")/.."

build=(bash scripts/build-web.sh)
first_frame=0
old_dist=
while (($#)); do
    case "$1" in
        --no-build) build=() ;;
        --rustup) build+=(--rustup) ;;
        --old)
            old_dist=$2
            shift
            ;;
        --first-frame)
            first_frame=10
            if [[ "${2:-}" =~ ^[0-9]+$ ]]; then
                first_frame=$2
                shift
            fi
            ;;
        *) break ;;
    esac
    shift
done
screenshot="${1:-target-web/web-screenshot.png}"
out="$(dirname "$screenshot")"
mkdir -p "$out"
timings="$out/web-timings.txt"

step() { printf '\n== %s (%ds)\n' "$1" "$SECONDS"; }

if ((${#build[@]})); then
    "${build[@]}"
fi
[ -f dist/index.html ] || { echo "no dist/: run scripts/build-web.sh" >&2; exit 1; }

# Only what is missing: a machine whose node comes from elsewhere (with its
# own npm) must not get Debian's nodejs/npm, which conflict with it.
need=()
command -v chromium >/dev/null 2>&1 || need+=(chromium)
command -v node >/dev/null 2>&1 || need+=(nodejs)
command -v npm >/dev/null 2>&1 || need+=(npm)
if ((${#need[@]})); then
    step "apt-get install ${need[*]}"
    sudo=()
    [ "$(id -u)" -eq 0 ] || sudo=(sudo)
    "${sudo[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq "${need[@]}"
fi
if [ ! -d tests/web/node_modules/playwright-core ]; then
    step "npm ci (playwright-core)"
    (cd tests/web && npm ci --no-audit --no-fund)
fi

# A free port on 127.0.0.1, and a server that goes away with this script.
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
python3 -m http.server -b 127.0.0.1 -d dist "$port" >/dev/null 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null || true' EXIT
python3 - "$port" <<'PY'
import sys, time, urllib.request
for _ in range(100):
    try:
        urllib.request.urlopen(f"http://127.0.0.1:{sys.argv[1]}/", timeout=1)
        break
    except OSError:
        time.sleep(0.1)
PY

if ((first_frame)); then
    if [ -n "$old_dist" ]; then
        old_port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
        python3 -m http.server -b 127.0.0.1 -d "$old_dist" "$old_port" >/dev/null 2>&1 &
        old_server=$!
        trap 'kill "$server" "$old_server" 2>/dev/null || true' EXIT
        export CDCA_OLD_URL="http://127.0.0.1:$old_port/"
        sleep 1
    fi
    step "first frame, $first_frame starts per scene, http://127.0.0.1:$port/"
    node tests/web/first_frame.mjs "http://127.0.0.1:$port/" "$out/web-first-frame.csv" "$first_frame"
    step "done"
    exit
fi
# the stepped pair's steps as `cdca grow` grows them natively, for the
# browser's Run growth to match (issue 63), where the native tool is built
cdca="${CARGO_TARGET_DIR:-target}/release/cdca"
if [ -x "$cdca" ] && [ -z "${CDCA_RUN_GROWTH_SCENE:-}" ]; then
    export CDCA_EXPECT_LOADS="$out/cdca-grow-loads.json"
    if ! "$cdca" grow assets/scenes/specimen_two_flaws_stepped.json |
        python3 -c 'import json, sys; print(json.dumps([s["load_factor"] for s in json.load(sys.stdin)["steps"]]))' \
            >"$CDCA_EXPECT_LOADS"; then
        echo "cdca grow failed: the browser's steps are checked against each other only" >&2
        unset CDCA_EXPECT_LOADS
    fi
fi
step "headless Chromium on http://127.0.0.1:$port/"
node tests/web/smoke.mjs "http://127.0.0.1:$port/" "$screenshot" "$timings"
step "layout at three sizes, loaded and resized"
node tests/web/layout.mjs "http://127.0.0.1:$port/" "$out"
step "a link after a run shares the scene as drawn"
node tests/web/link.mjs "http://127.0.0.1:$port/"
step "done"
