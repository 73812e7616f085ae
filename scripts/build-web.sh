#!/usr/bin/env bash
# Builds the workbench for the browser into dist/ (a static site: index.html,
# worker.js, cdca-workbench.js, cdca-workbench_bg.wasm) on a Debian 12 machine without
# rustup's wasm target, installing what it needs:
#   - Debian's rustc-web (a rustc with the WebAssembly backend), the matching
#     std sources (rust-web-src) and wasm-ld (lld-22); std is built from
#     source with -Zbuild-std;
#   - wasm-bindgen-cli at the version Cargo.lock pins (cargo install);
#   - binaryen's wasm-opt from npm (scripts/wasm-opt, run on node; Debian's
#     binaryen 108 produces output Chromium rejects), which shrinks the
#     bundle by 7% (docs/browser.md), and terser, which minifies the
#     bindings.
#
# With rustup's wasm32 target, `trunk build --release` does the same (see the
# docs/browser.md), and so does `--rustup`: the wasm build with rustup's
# compiler and its prebuilt std (no Debian compiler packages; no
# -Zlocation-detail, which needs a nightly compiler: about 0.1 MiB more),
# into $CARGO_TARGET_DIR or target-web-rustup; the rest as below.
#
# Usage: scripts/build-web.sh [--rustup]   (serve with:
#        python3 -m http.server -b 127.0.0.1 -d dist 8080)
set -euo pipefail
cd "$(dirname "$0")/.."

rustup_target=0
if [ "${1:-}" = "--rustup" ]; then
    rustup_target=1
fi

app=cdca-workbench
profile=web # Cargo.toml [profile.web]: release + LTO, for a smaller bundle
wasm_ld=/usr/lib/llvm-22/bin/wasm-ld
packages=()
((rustup_target)) || packages+=(rustc-web cargo-web rust-web-src lld-22)
# node and npm only where missing: a machine whose node comes from elsewhere
# (with its own npm) must not get Debian's, which conflict with it.
command -v node >/dev/null 2>&1 || packages+=(nodejs)
command -v npm >/dev/null 2>&1 || packages+=(npm)

step() { printf '\n== %s (%ds)\n' "$1" "$SECONDS"; }

# --- 1. Debian packages ------------------------------------------------------
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if ((${#missing[@]})); then
    step "apt-get install ${missing[*]}"
    sudo=()
    [ "$(id -u)" -eq 0 ] || sudo=(sudo)
    "${sudo[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq "${missing[@]}"
fi

# --- 2. wasm-bindgen-cli matching the wasm-bindgen crate ---------------------
if ! command -v cargo >/dev/null 2>&1 && [ -f "$HOME/.cargo/env" ]; then
    # shellcheck source=/dev/null
    . "$HOME/.cargo/env"
fi
bindgen_version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/[^0-9.]/, ""); print; exit }' Cargo.lock)
[ -n "$bindgen_version" ] || { echo "no wasm-bindgen in Cargo.lock" >&2; exit 1; }
export PATH="$HOME/.cargo/bin:$PATH"
if [ "$(wasm-bindgen --version 2>/dev/null | awk '{ print $2 }')" != "$bindgen_version" ]; then
    step "cargo install wasm-bindgen-cli $bindgen_version"
    # Not --locked: the registry index lacks one of its pinned dependencies.
    cargo install wasm-bindgen-cli --version "$bindgen_version"
fi

# --- 3. The wasm build -------------------------------------------------------
step "cargo build --target wasm32-unknown-unknown --profile $profile"
if ((rustup_target)); then
    target_dir="${CARGO_TARGET_DIR:-target-web-rustup}"
    CARGO_TARGET_DIR="$target_dir" cargo build --target wasm32-unknown-unknown \
        --profile "$profile" --bin "$app"
else
    target_dir=target-web
    # RUSTC etc. only for this command: exported, they would switch native
    # builds to Debian's compiler. -Zlocation-detail=none: panics keep
    # their message but not the source file, line and column (about 0.1 MiB
    # of strings). RUSTFLAGS replaces .cargo/config.toml's flags for the
    # target, so WebAssembly SIMD (+simd128) is asked for here too; std,
    # built here from source, gets it as well.
    RUSTC=/usr/bin/rustc RUSTDOC=/usr/bin/rustdoc RUSTC_BOOTSTRAP=1 \
        RUSTFLAGS="-Zlocation-detail=none -C target-feature=+simd128" \
        CARGO_TARGET_DIR="$target_dir" \
        CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_LINKER="$wasm_ld" \
        /usr/bin/cargo build --target wasm32-unknown-unknown --profile "$profile" \
        -Zbuild-std=std,panic_abort --bin "$app"
fi

# --- 4. JS bindings and the page ---------------------------------------------
step "wasm-bindgen"
rm -rf dist
mkdir -p dist
# Without the name section (function names, ~0.6 MiB): panics still show
# their message in the console, with fewer names in the stack trace.
wasm-bindgen --target web --no-typescript --remove-name-section \
    --out-dir dist --out-name "$app" \
    "$target_dir/wasm32-unknown-unknown/$profile/$app.wasm"
# index.html serves trunk and this script: drop trunk's <link data-trunk>
# lines and load the bindings ourselves.
loader="<script type=\"module\">import init from \"./$app.js\"; init().catch((e) => window.cdcaLoadFailed(e));</script>"
sed -e '/data-trunk/d' -e "s#<!-- build-web.sh: loader -->#$loader#" index.html >dist/index.html
grep -q "import init" dist/index.html || { echo "index.html lacks the loader marker" >&2; exit 1; }
# The solver's Web Worker (src/run/worker.rs): the same module, whose main
# finds no window and serves the page's requests.
cp worker.js dist/worker.js

# Binaryen's size optimisation on the bound module (the features are what
# rustc's wasm32 target emits, with SIMD). Measured: 7% smaller, Run
# growth no slower.
if [ ! -x scripts/wasm-opt/node_modules/.bin/wasm-opt ] || [ ! -x scripts/wasm-opt/node_modules/.bin/terser ]; then
    step "npm ci (binaryen)"
    (cd scripts/wasm-opt && npm ci --no-audit --no-fund)
fi
step "wasm-opt -Os"
scripts/wasm-opt/node_modules/.bin/wasm-opt -Os \
    --enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext \
    --enable-mutable-globals --enable-reference-types --enable-multivalue --enable-simd \
    "dist/${app}_bg.wasm" -o "dist/${app}_bg.wasm"

# The bindings minified (terser, from the same npm package): 85 KB → 40 KB,
# which keeps the page's download (the module, its bindings, index.html and
# worker.js) within 4.5 MB with the solver's Web Worker protocol.
step "terser"
scripts/wasm-opt/node_modules/.bin/terser "dist/$app.js" --module --compress --mangle \
    -o "dist/$app.min.js"
mv "dist/$app.min.js" "dist/$app.js"

wasm_bytes=$(stat -c %s "dist/${app}_bg.wasm")
page_bytes=$(cat dist/* | wc -c)
gz_bytes=$(gzip -9 -c "dist/${app}_bg.wasm" | wc -c)
step "done"
awk -v a="$app" -v w="$wasm_bytes" -v g="$gz_bytes" -v p="$page_bytes" \
    'BEGIN { printf "dist/%s_bg.wasm: %.2f MiB (%.2f MiB gzipped); the page in all: %d bytes\n", a, w / 1048576, g / 1048576, p }'
echo "serve with: python3 -m http.server -b 127.0.0.1 -d dist 8080"
