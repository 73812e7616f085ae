#!/usr/bin/env bash
# Grows the three bundled two-flaw specimens (critical control) and draws
# their final crack paths side by side into assets/two_flaw_paths.svg (and
# a PNG next to it when rsvg-convert or ImageMagick's convert is present).
# Usage: bash scripts/paths_figure.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p cdca-cli
out=$(mktemp -d)
svg=assets/two_flaw_paths.svg
layouts=(coplanar stepped overlapping)
for l in "${layouts[@]}"; do
  # exit 1 (a step that did not converge) still leaves the paths so far
  ./target/release/cdca grow "assets/scenes/specimen_two_flaws_$l.json" --csv "$out/$l" \
    >"$out/$l.json" || echo "$l: growth stopped early (see its JSON)" >&2
done
{
  echo '<svg xmlns="http://www.w3.org/2000/svg" width="960" height="360" font-family="sans-serif" font-size="14">'
  echo '<rect width="960" height="360" fill="white"/>'
  i=0
  for l in "${layouts[@]}"; do
    x0=$((20 + i * 320))
    # the specimen: 30 mm -> 300 px, y up
    echo "<g transform=\"translate($x0,330) scale(10000,-10000)\">"
    echo '<rect x="0" y="0" width="0.03" height="0.03" fill="#f4f1ea" stroke="black" stroke-width="0.0001"/>'
    awk -F, 'NR > 1 {
        if (!s || $1 != c) { s = 1; if (p != "") print p "\" fill=\"none\" stroke=\"#b22\" stroke-width=\"0.00015\"/>"; p = "<polyline points=\""; c = $1 }
        p = p $3 "," $4 " "
      } END { if (p != "") print p "\" fill=\"none\" stroke=\"#b22\" stroke-width=\"0.00015\"/>" }' "$out/$l/cracks.csv"
    echo '</g>'
    echo "<text x=\"$((x0 + 150))\" y=\"20\" text-anchor=\"middle\">$l</text>"
    i=$((i + 1))
  done
  echo '</svg>'
} >"$svg"
echo "wrote $svg"
if command -v rsvg-convert >/dev/null; then
  rsvg-convert "$svg" -o "${svg%.svg}.png" && echo "wrote ${svg%.svg}.png"
elif command -v convert >/dev/null; then
  convert "$svg" "${svg%.svg}.png" && echo "wrote ${svg%.svg}.png"
fi
rm -rf "$out"
