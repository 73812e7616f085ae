#!/usr/bin/env bash
# Grows the three bundled two-flaw specimens (critical control) and draws
# their final crack paths side by side into assets/two_flaw_paths.svg (and
# a PNG next to it when rsvg-convert or ImageMagick's convert is present):
# the initial flaws in black, the grown paths in red, junctions as dots.
# Usage: bash scripts/paths_figure.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p cdca-cli
out=$(mktemp -d)
svg=assets/two_flaw_paths.svg
layouts=(coplanar stepped overlapping)
for l in "${layouts[@]}"; do
  # exit 1 (a step that did not converge) still leaves the paths so far
  ./target/release/cdca grow "assets/scenes/specimen_two_flaws_$l.json" \
    >"$out/$l.json" || echo "$l: growth stopped early (see its JSON)" >&2
done
python3 - "$out" "$svg" "${layouts[@]}" <<'PY'
import json, sys
out, svg, layouts = sys.argv[1], sys.argv[2], sys.argv[3:]
W, PANEL, GAP, TOP = 300, 300, 30, 40
width = GAP + len(layouts) * (PANEL + GAP)
s = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{PANEL + TOP + 40}" font-family="sans-serif" font-size="14">',
     f'<rect width="{width}" height="{PANEL + TOP + 40}" fill="white"/>']
for i, l in enumerate(layouts):
    scene = json.load(open(f"assets/scenes/specimen_two_flaws_{l}.json"))
    run = json.load(open(f"{out}/{l}.json"))
    x0, scale = GAP + i * (PANEL + GAP), PANEL / scene["specimen"]["width"]
    px = lambda p: f"{x0 + p[0] * scale:.2f},{TOP + PANEL - p[1] * scale:.2f}"
    s.append(f'<rect x="{x0}" y="{TOP}" width="{PANEL}" height="{PANEL}" fill="#f4f1ea" stroke="black"/>')
    for c in run["cracks"]:
        s.append(f'<polyline points="{" ".join(px(p) for p in c)}" fill="none" stroke="#b22" stroke-width="1.5"/>')
    for c in scene["cracks"]:
        s.append(f'<polyline points="{" ".join(px(p) for p in c["points"])}" fill="none" stroke="black" stroke-width="3"/>')
    joined = 0
    for step in run["steps"]:
        for g in step["grown"]:
            # a grown tip that ended on another crack: a junction
            p = [g["x"], g["y"]]
            on = [k for k, c in enumerate(run["cracks"]) if k != g["crack"] and any(
                abs((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])) < 1e-12
                and min(q[0], r[0]) - 1e-9 <= p[0] <= max(q[0], r[0]) + 1e-9
                and min(q[1], r[1]) - 1e-9 <= p[1] <= max(q[1], r[1]) + 1e-9
                for q, r in zip(c, c[1:]))]
            if on:
                joined += 1
                s.append(f'<circle cx="{px(p).split(",")[0]}" cy="{px(p).split(",")[1]}" r="5" fill="none" stroke="#15c" stroke-width="2"/>')
    s.append(f'<text x="{x0 + PANEL / 2}" y="{TOP - 12}" text-anchor="middle">{l}</text>')
    s.append(f'<text x="{x0 + PANEL / 2}" y="{TOP + PANEL + 22}" text-anchor="middle" font-size="12">'
             f'{len(run["steps"])} steps, {run["outcome"]}, {joined} junction{"s" * (joined != 1)}</text>')
s.append('</svg>')
open(svg, "w").write("\n".join(s) + "\n")
PY
echo "wrote $svg"
if command -v rsvg-convert >/dev/null; then
  rsvg-convert "$svg" -o "${svg%.svg}.png" && echo "wrote ${svg%.svg}.png"
elif command -v convert >/dev/null; then
  convert "$svg" "${svg%.svg}.png" && echo "wrote ${svg%.svg}.png"
fi
rm -rf "$out"
