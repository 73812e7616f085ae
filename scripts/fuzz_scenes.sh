#!/usr/bin/env bash
# Bad and awkward input on purpose (docs/scene-files.md): scenes made
# from the bundled ones and run through `cdca validate`, `cdca solve` and
# `cdca grow` (three steps, under load or critical control at random),
# each checked for what must never happen: a panic or an abort, an exit
# code other than 0 (trusted), 1 (did not converge, says why) or 2 (bad
# input, one line naming the field), a `null` (a NaN or an infinity) in a
# report, a scene `validate` accepts that `solve` or `grow` refuses as bad
# input, or a hang (60 s). Four kinds of scene:
#   fields     one to three fields of five bundled scenes set at random
#              (zero, negated, tiny, huge, scaled, wrong type, deleted);
#   extremes   every numeric field of the default and the stepped scene set
#              to 1e-310, 1e-300, 1e300 and 1.7e308 in turn (all of them, or
#              with --ci a seeded sample of EXTREMES);
#   materials  extreme rocks on the bundled pairs: cohesion, tensile
#              strength, toughness, friction angle, Young's modulus and
#              Poisson's ratio from their edges of validity to 1e±12 of
#              the bundled values, one to three at once;
#   geometry   1-3 random polylines on the default specimen: snapped to
#              nodes or element edges, from the boundary, touching another
#              crack, with segments of 1e-3 h to 3 h, stiff joints and
#              extreme friction, on meshes of 10-61 elements a side.
# Prints every run that is not a clean exit 0 or 2 with its scene (JSON)
# when it is a failure, and a summary per kind; exits 1 if any run failed.
# Usage: bash scripts/fuzz_scenes.sh [COUNT] [SEED] [--ci]
#   (default 100, 1; --ci: the short seeded run .ci/run makes, COUNT per
#   kind and 24 extremes)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p cdca-cli
CI_RUN=0
args=()
for a in "$@"; do
    if [ "$a" = --ci ]; then CI_RUN=1; else args+=("$a"); fi
done
COUNT="${args[0]:-100}" SEED="${args[1]:-1}" CI_RUN="$CI_RUN" python3 - <<'PY'
import collections, json, math, os, random, subprocess, sys, tempfile, time
count, seed = int(os.environ["COUNT"]), int(os.environ["SEED"])
ci = os.environ["CI_RUN"] == "1"
started = time.time()
failures = []
rng = random.Random(seed)
scenes = "assets/scenes/"
bases = ["specimen_single_flaw", "centre_crack_tension", "closed_crack_biaxial",
         "specimen_two_flaws_stepped", "edge_crack_tension"]
load = lambda name: json.load(open(f"{scenes}{name}.json"))
work = tempfile.mkdtemp(prefix="cdca-fuzz-")

def leaves(o, path=()):
    if isinstance(o, dict):
        for k, v in o.items():
            yield from leaves(v, path + (k,))
    elif isinstance(o, list):
        for i, v in enumerate(o):
            yield from leaves(v, path + (i,))
    else:
        yield path, o

def put(o, path, v):
    for p in path[:-1]:
        o = o[p]
    o[path[-1]] = v

def cdca(command, path):
    try:
        p = subprocess.run(["target/release/cdca", command, path],
                           capture_output=True, text=True, timeout=60)
        return p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired:
        return "hang", "", ""

def run(kind, scene, command, what, tally):
    path = os.path.join(work, "scene.json")
    json.dump(scene, open(path, "w"))
    code, out, err = cdca(command, path)
    bad = []
    if code not in (0, 1, 2):
        bad.append(f"exit {code}")
    if "panicked" in err:
        bad.append("panic")
    if code in (0, 1) and "null" in out.replace('"error": null', ""):
        bad.append("null in the report")
    if code == 2 and not (err.startswith("cdca: ") and err.count("\n") == 1):
        bad.append("not one line")
    if code == 2 and not bad:
        # bad input is refused before any work: validate says so too
        vcode, _, _ = cdca("validate", path)
        if vcode != 2 and "growth stopped" not in err:
            bad.append(f"validate accepts what {command} refuses")
    tally[kind][("BAD " + ", ".join(bad)) if bad else f"exit {code}"] += 1
    if bad or code == 1:
        last = (err.strip().splitlines() or [""])[-1]
        print(f"{kind:9s} {command:5s} {'BAD ' + ', '.join(bad) if bad else 'exit 1'}: {what}\n"
              f"          {last[:200]}", flush=True)
        json.dump(scene, open(os.path.join(work, f"{kind}-{sum(tally[kind].values())}.json"), "w"))
    if bad:
        failures.append(what)
        print(f"          scene: {json.dumps(scene)}", flush=True)

def grow_settings(s, rng):
    g = s.setdefault("growth", {})
    g["max_steps"] = 3
    g["control"] = rng.choice(["load", "critical"])

tally = collections.defaultdict(collections.Counter)
values = [0, -1, 1, 1e-300, 1e300, 2**62, "abc", None, True]
for i in range(count):
    s = load(rng.choice(bases))
    command = rng.choice(["solve", "solve", "grow"])
    if command == "grow":
        grow_settings(s, rng)
    what = []
    for _ in range(rng.choice([1, 1, 2, 3])):
        path, v = rng.choice(list(leaves(s)))
        if path[-1] in ("name", "description"):
            continue
        if isinstance(v, (int, float)) and not isinstance(v, bool) and rng.random() < 0.5:
            new = v * rng.choice([-1, 1e-6, 1e6, 1 + rng.uniform(-0.5, 0.5)])
        else:
            new = rng.choice(values + ["", "bogus", "direct", "strain", "roller", "xy"])
        put(s, path, new)
        what.append(f"{'.'.join(map(str, path))} = {new!r}")
    run("fields", s, command, "; ".join(what), tally)

extremes = []
for name, command in [("specimen_single_flaw", "solve"), ("specimen_two_flaws_stepped", "grow")]:
    base = load(name)
    for path, v in leaves(base):
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            continue
        for new in [1e-310, 1e-300, 1e300, 1.7e308]:
            extremes.append((name, command, path, new))
if ci:
    extremes = rng.sample(extremes, min(24, len(extremes)))
for name, command, path, new in extremes:
    s = load(name)
    grow_settings(s, rng)
    put(s, path, new)
    run("extremes", s, command, f"{name}: {'.'.join(map(str, path))} = {new!r}", tally)

pairs = ["specimen_two_flaws_coplanar", "specimen_two_flaws_stepped",
         "specimen_two_flaws_overlapping"]
rock = {"cohesion": [1e-12, 0.5, 1.0, 1e3, 1e5, 1e9, 1e12],
        "tensile_strength": [1e-3, 1.0, 1e3, 1e5, 1e9, 1e12],
        "k_ic": [1e-6, 1e2, 1e4, 1e9, 1e12],
        "friction_angle_deg": [0.0, 1e-9, 30.0, 60.0, 89.9],
        "young": [1e3, 1e6, 1e15],
        "poisson": [-0.99, 0.0, 0.49]}
for i in range(count):
    s = load(rng.choice(pairs))
    s["mesh"] = {"nx": rng.choice([30, 40, 50]), "ny": rng.choice([30, 40, 50])}
    what = []
    for field in rng.sample(sorted(rock), rng.choice([1, 1, 2, 3])):
        s["material"][field] = rng.choice(rock[field])
        what.append(f"material.{field} = {s['material'][field]!r}")
    command = rng.choice(["validate", "solve", "grow", "grow"])
    grow_settings(s, rng)
    run("materials", s, command, "; ".join(what), tally)

width = 0.03
for i in range(count):
    s = load("specimen_single_flaw")
    n = rng.choice([10, 20, 41, 60, 61])
    s["mesh"] = {"nx": n, "ny": rng.choice([n, n, n + 1])}
    h = width / n
    cracks = []
    for _ in range(rng.choice([1, 1, 2, 3])):
        mode = rng.choice(["free", "node", "edge", "boundary"])
        x, y = rng.uniform(0.002, 0.028), rng.uniform(0.002, 0.028)
        points = []
        for j in range(rng.choice([2, 2, 3, 4])):
            if j:
                step = rng.choice([rng.uniform(0.002, 0.01), 1e-3 * h, 0.5 * h, h, 3 * h])
                a = rng.choice([rng.uniform(0, math.pi), 0, math.pi / 2, math.pi / 4])
                x, y = x + step * math.cos(a), y + step * math.sin(a)
            if mode == "node":
                x, y = round(x / h) * h, round(y / h) * h
            if mode == "edge":
                y = round(y / h) * h
            points.append([min(max(x, 0.0), width), min(max(y, 0.0), width)])
        if mode == "boundary":
            points[0][rng.choice([0, 1])] = rng.choice([0.0, width])
        if cracks and rng.random() < 0.3:
            points[0] = list(rng.choice(cracks[-1]["points"]))
        crack = {"points": points, "friction": rng.choice([0, 0.3, 0.6, 5.0])}
        if rng.random() < 0.2:
            crack["normal_stiffness"] = rng.choice([200e9, 1e12, 1e16])
        cracks.append(crack)
    s["cracks"] = cracks
    if rng.random() < 0.3:
        s["boundary"]["right"] = {"kind": "traction", "normal": -rng.choice([0, 10e6, 50e6]),
                                  "shear": rng.choice([0, 5e6])}
    command = rng.choice(["solve", "solve", "grow"])
    grow_settings(s, rng)
    run("geometry", s, command, f"geometry {i}", tally)

for kind, counts in tally.items():
    print(f"{kind}: " + ", ".join(f"{k}: {v}" for k, v in sorted(counts.items())))
print(f"scenes that were not a clean exit 0 or 2 are kept in {work}")
runs = sum(sum(c.values()) for c in tally.values())
print(f"fuzz: seed {seed}, {runs} runs, {len(failures)} failed, {time.time() - started:.0f} s")
sys.exit(1 if failures else 0)
PY
