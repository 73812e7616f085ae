#!/usr/bin/env bash
# The bundled specimens (the single flaw and the three two-flaw pairs,
# critical control) grown by both models of the intact rock, side by side,
# into assets/two_flaw_paths.svg: the final paths under the paper's model
# (growth.intact_rock = "ignore": tips and kinks only) in the first row and
# with the intact rock failing ("nucleate") in the second (flaws black,
# wings and secondary cracks red, cracks started in the intact rock blue,
# junctions as dots), and the load factor per step of both in the third,
# against the load at which the uncracked specimen fails (dashed).
# Usage: bash scripts/paths_figure.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q --workspace
out=$(mktemp -d)
svg=assets/two_flaw_paths.svg
scenes=(specimen_single_flaw specimen_two_flaws_coplanar specimen_two_flaws_stepped specimen_two_flaws_overlapping)
for s in "${scenes[@]}"; do
  for model in ignore nucleate; do
    python3 -c "import json,sys; d=json.load(open('assets/scenes/$s.json')); d['growth']['intact_rock']='$model'; json.dump(d,open('$out/${s}_$model.scene.json','w'))"
    # exit 1 (a step that did not converge) still leaves the paths so far
    ./target/release/cdca grow "$out/${s}_$model.scene.json" >"$out/${s}_$model.json" 2>/dev/null ||
      echo "$s ($model): growth stopped early (see its JSON)" >&2
  done
done
python3 - "$out" "$svg" "${scenes[@]}" <<'PY'
import json, sys
out, svg, scenes = sys.argv[1], sys.argv[2], sys.argv[3:]
PANEL, GAP, TOP, PLOT = 240, 30, 40, 160
titles = {"specimen_single_flaw": "single flaw", "specimen_two_flaws_coplanar": "coplanar pair",
          "specimen_two_flaws_stepped": "stepped pair", "specimen_two_flaws_overlapping": "overlapping pair"}
width = GAP + len(scenes) * (PANEL + GAP)
height = TOP + 2 * (PANEL + GAP) + PLOT + 70
s = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="13">',
     f'<rect width="{width}" height="{height}" fill="white"/>']
colour = {"flaw": "black", "wing": "#c0392b", "secondary": "#c0392b", "intact": "#1f5fa8"}
for i, name in enumerate(scenes):
    scene = json.load(open(f"{out}/{name}_ignore.scene.json"))
    x0 = GAP + i * (PANEL + GAP)
    s.append(f'<text x="{x0 + PANEL / 2}" y="{TOP - 14}" text-anchor="middle" font-weight="bold">{titles.get(name, name)}</text>')
    runs = {}
    for row, model in enumerate(("ignore", "nucleate")):
        run = json.load(open(f"{out}/{name}_{model}.json"))
        runs[model] = run
        y0 = TOP + row * (PANEL + GAP)
        scale = PANEL / scene["specimen"]["width"]
        px = lambda p: f"{x0 + p[0] * scale:.2f},{y0 + PANEL - p[1] * scale:.2f}"
        s.append(f'<rect x="{x0}" y="{y0}" width="{PANEL}" height="{PANEL}" fill="#f4f1ea" stroke="black"/>')
        drawn = len(scene["cracks"])
        starts = {n["crack"] for st in run["steps"] for n in st.get("nucleated", [])}
        for k, c in enumerate(run["cracks"]):
            col = "black" if k < drawn else ("#1f5fa8" if k in starts else "#c0392b")
            if k < drawn:
                # the drawn flaw black, what grew at its ends red
                s.append(f'<polyline points="{" ".join(px(p) for p in c)}" fill="none" stroke="#c0392b" stroke-width="2"/>')
                flaw = scene["cracks"][k]["points"]
                s.append(f'<polyline points="{" ".join(px(p) for p in flaw)}" fill="none" stroke="black" stroke-width="2.5"/>')
            else:
                s.append(f'<polyline points="{" ".join(px(p) for p in c)}" fill="none" stroke="{col}" stroke-width="2"/>')
        for st in run["steps"]:
            for l in st.get("links", []):
                c = run["cracks"][l["crack"]]
                p = px(c[0] if l["tip"] == 0 else c[-1]).split(",")
                s.append(f'<circle cx="{p[0]}" cy="{p[1]}" r="3" fill="black"/>')
        label = "paper's model (ignore)" if model == "ignore" else "intact rock fails (nucleate)"
        st = run.get("strength") or {}
        peak = f", peak λ {st['peak_load_factor']:.2f}" if st else ""
        s.append(f'<text x="{x0 + 4}" y="{y0 + 16}" font-size="12">{label}</text>')
        s.append(f'<text x="{x0 + 4}" y="{y0 + PANEL - 6}" font-size="12">{run["outcome"]}, {len(run["steps"])} steps{peak}</text>')
    # load factor per step, both models, and the uncracked specimen's
    y0 = TOP + 2 * (PANEL + GAP)
    s.append(f'<rect x="{x0}" y="{y0}" width="{PANEL}" height="{PLOT}" fill="white" stroke="black"/>')
    steps = max(len(r["steps"]) for r in runs.values())
    intact = (runs["nucleate"].get("strength") or {}).get("intact_load_factor")
    top = max([st["load_factor"] for r in runs.values() for st in r["steps"] if st["grown"] or st.get("nucleated") or st.get("started")] + [intact or 0])
    top = min(top, 3.0 * (intact or top)) * 1.1
    X = lambda k: x0 + (k - 1) / max(steps - 1, 1) * PANEL
    Y = lambda v: y0 + PLOT - min(v, top) / top * PLOT
    if intact:
        s.append(f'<line x1="{x0}" y1="{Y(intact):.1f}" x2="{x0 + PANEL}" y2="{Y(intact):.1f}" stroke="gray" stroke-dasharray="5,4"/>')
        s.append(f'<text x="{x0 + PANEL - 4}" y="{Y(intact) - 4:.1f}" text-anchor="end" font-size="11" fill="#555">uncracked λ {intact:.2f}</text>')
    for model, col in (("ignore", "#c0392b"), ("nucleate", "#1f5fa8")):
        pts = [(st["step"], st["load_factor"]) for st in runs[model]["steps"]]
        s.append(f'<polyline points="{" ".join(f"{X(k):.1f},{Y(v):.1f}" for k, v in pts)}" fill="none" stroke="{col}" stroke-width="1.8"/>')
    s.append(f'<text x="{x0}" y="{y0 + PLOT + 16}" font-size="11">step 1</text>')
    s.append(f'<text x="{x0 + PANEL}" y="{y0 + PLOT + 16}" text-anchor="end" font-size="11">{steps}</text>')
    s.append(f'<text x="{x0 + 4}" y="{y0 + 14}" font-size="11">λ (0 to {top:.2f})</text>')
y = TOP + 2 * (PANEL + GAP) + PLOT + 44
s.append(f'<text x="{GAP}" y="{y}" font-size="12">flaws black; wings and secondary cracks red; cracks started in the intact rock blue; '
         f'load factor per step: paper\'s model red, intact rock failing blue (capped at 3 times the uncracked specimen\'s)</text>')
s.append("</svg>")
open(svg, "w").write("\n".join(s))
print(f"wrote {svg}")
PY
if command -v rsvg-convert >/dev/null 2>&1; then
  rsvg-convert "$svg" -o "${svg%.svg}.png"
elif command -v convert >/dev/null 2>&1; then
  convert "$svg" "${svg%.svg}.png"
fi
rm -rf "$out"
