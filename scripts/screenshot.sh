#!/usr/bin/env bash
# Runs the workbench under a virtual X display and saves a screenshot of the
# whole screen (used by the README and docs/).
#
#   bash scripts/screenshot.sh [SECONDS] [OUT.png] [-- WORKBENCH ARGS...]
#
# SECONDS: wait before the shot (default 8); OUT.png: default
# assets/screenshot.png; the workbench arguments, e.g.
#   bash scripts/screenshot.sh 6 assets/relax.png -- scene.json --run relax
#
# CDCA_SHOT_SIZE=WxH sets the screen's and the window's size (default
# 1400x900), e.g. CDCA_SHOT_SIZE=390x844 for a phone's.
#
# Installs what it needs with apt-get when missing: xvfb, imagemagick and the
# run-time libraries of winit + glow (X cursor/input, xkbcommon, EGL/GL Mesa).
set -euo pipefail
cd "$(dirname "$0")/.."

wait_s="8"
out="assets/screenshot.png"
if [[ $# -gt 0 && "$1" != "--" ]]; then wait_s="$1"; shift; fi
if [[ $# -gt 0 && "$1" != "--" ]]; then out="$1"; shift; fi
[[ $# -gt 0 && "$1" == "--" ]] && shift
app_args=("$@")
size="${CDCA_SHOT_SIZE:-1400x900}"

need=()
command -v Xvfb >/dev/null || need+=(xvfb)
command -v import >/dev/null || need+=(imagemagick)
for lib in libXcursor.so.1 libXi.so.6 libxkbcommon-x11.so.0 libEGL.so.1; do
    ldconfig -p | grep -q "$lib" || need+=(libxcursor1 libxi6 libxkbcommon-x11-0 libegl1 libegl-mesa0 libgl1-mesa-dri)
done
if ((${#need[@]})); then
    echo "installing: $(printf '%s\n' "${need[@]}" | sort -u | tr '\n' ' ')"
    sudo_cmd=""
    [[ $(id -u) -ne 0 ]] && sudo_cmd="sudo"
    $sudo_cmd apt-get update -qq
    # shellcheck disable=SC2046
    $sudo_cmd apt-get install -y -qq $(printf '%s\n' "${need[@]}" | sort -u)
fi

cargo build --release --bin cdca-workbench
bin="${CARGO_TARGET_DIR:-target}/release/cdca-workbench"

display=":$((90 + RANDOM % 9))"
Xvfb "$display" -screen 0 "${size}x24" -nolisten tcp &
xvfb_pid=$!
app_pid=""
cleanup() {
    [[ -n "$app_pid" ]] && kill "$app_pid" 2>/dev/null || true
    kill "$xvfb_pid" 2>/dev/null || true
}
trap cleanup EXIT
sleep 1

# A fresh persistence directory, so the shot shows the default scene, and
# Mesa's software renderer (no GPU on CI machines).
data_dir="$(mktemp -d)"
DISPLAY="$display" XDG_DATA_HOME="$data_dir" HOME="$data_dir" \
    LIBGL_ALWAYS_SOFTWARE=1 WINIT_UNIX_BACKEND=x11 WAYLAND_DISPLAY= \
    "$bin" --size "$size" "${app_args[@]}" &
app_pid=$!
sleep "$wait_s"
if ! kill -0 "$app_pid" 2>/dev/null; then
    echo "the workbench exited early" >&2
    exit 1
fi
DISPLAY="$display" import -window root "$out"
echo "saved $out"
