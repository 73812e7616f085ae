#!/usr/bin/env bash
# Writes assets/fonts/Ubuntu-Light-derivative-CDCA.ttf, the app's text font (src/app/mod.rs,
# `fonts`): egui's Ubuntu Light (from the epaint_default_fonts crate in the
# cargo registry) cut to the scripts a scene name or a message may use:
# Latin-1 and Latin Extended-A, Greek, basic Cyrillic, general punctuation,
# super- and subscripts, letterlike symbols, mathematical operators
# and geometric shapes; kerning and the other layout features kept, TrueType
# hinting dropped (egui's rasteriser then auto-hints). 362 KiB -> 88 KiB of
# the browser bundle. Uses fontTools' subsetter, installed from PyPI into a
# temporary directory. Run it again only if egui's font or the ranges change;
# the app's font test checks that every character the code writes is there.
# The Ubuntu Font Licence (assets/fonts/UFL.txt, 2c) asks that a modified
# version keep the original's name with "derivative X" appended: the name
# table says "Ubuntu Light derivative CDCA".
#
#   bash scripts/subset_font.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo fetch -q
src=$(ls -d "${CARGO_HOME:-$HOME/.cargo}"/registry/src/*/epaint_default_fonts-0.37.0/fonts | head -n 1)
tools=$(mktemp -d)
trap 'rm -rf "$tools"' EXIT
python3 -m pip install --quiet --target "$tools" fonttools==4.68.0
PYTHONPATH="$tools" python3 -m fontTools.subset "$src/Ubuntu-Light.ttf" \
    --unicodes="U+0020-007E,U+00A0-017F,U+0370-03FF,U+0400-045F,U+2000-206F,U+2070-209F,U+20AC,U+2100-214F,U+2190-21FF,U+2200-22FF,U+25A0-25FF,U+FFFD" \
    --layout-features='*' --no-hinting \
    --output-file="$tools/subset.ttf"
PYTHONPATH="$tools" python3 - "$tools/subset.ttf" assets/fonts/Ubuntu-Light-derivative-CDCA.ttf <<'PY'
import sys
from fontTools.ttLib import TTFont
font = TTFont(sys.argv[1])
names = font["name"]
for record in list(names.names):
    text = record.toUnicode()
    if record.nameID in (1, 3, 4, 16, 18):
        record.string = text.replace("Ubuntu Light", "Ubuntu Light derivative CDCA") \
            if "Ubuntu Light" in text else text.replace("Ubuntu", "Ubuntu derivative CDCA")
    elif record.nameID == 6:
        record.string = text.replace("Ubuntu", "UbuntuDerivativeCDCA")
font.save(sys.argv[2])
print({r.nameID: r.toUnicode() for r in font["name"].names if r.nameID in (1, 4, 6)})
PY
cp "$src/UFL.txt" assets/fonts/UFL.txt
ls -l assets/fonts/Ubuntu-Light-derivative-CDCA.ttf
