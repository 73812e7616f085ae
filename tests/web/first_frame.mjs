// The browser's first frame and first solved field (issue 54), as
// scripts/first_frame.sh measures them natively: over STARTS starts per
// scene (a fresh page and profile each), the time from the navigation to
// the first frame laid out (the scene's geometry and the controls) and to
// the first field shown, as the app notes them (performance.now(), i.e.
// since the navigation began: window.cdcaState.firstFrameMs and
// firstFieldMs, src/app/web.rs). The scenes are first_frame.sh's: the default
// scene, the bundled k = 0.2, μ = 0.5 plate at 120 × 120 with the
// automaton solver and at 200 × 200 with the direct solver, the two
// plates opened as shared links (`#scene=…`). Prints a row per scene
// (median and largest of each) and writes OUT.csv. With CDCA_OLD_URL (an
// older bundle served beside this one: `scripts/test-web.sh --first-frame
// N --old DIR`), the two bundles' starts alternate and each scene gets a
// row per bundle and their medians' differences (issue 63: the solver's
// worker may cost the first frame and field at most 0.2 s).
//
//   node tests/web/first_frame.mjs URL OUT.csv [STARTS]
import { writeFileSync } from "node:fs";
import { START_TIMEOUT_MS, launch, log, medianMax, open, problems, sceneLink, watch } from "./common.mjs";

const [url, outPath, startsArg] = process.argv.slice(2);
if (!url || !outPath) {
    console.error("usage: node first_frame.mjs URL OUT.csv [STARTS]");
    process.exit(2);
}
const starts = Number(startsArg ?? 10);

const plate = (name, n, kind) =>
    sceneLink("plate_45_biaxial_k0.2_mu0.5.json", (s) => ({
        ...s,
        name,
        mesh: { ...s.mesh, nx: n, ny: n },
        solver: { kind },
    }));
// [row label, CSV name (as first_frame.sh's), page address fragment]
const scenes = [
    ["default (60 × 60, direct)", "specimen_single_flaw", ""],
    ["plate 120 × 120, automaton", "plate_120_automaton", `#${plate("plate_120_automaton", 120, "automaton")}`],
    ["plate 200 × 200, direct", "plate_200_direct", `#${plate("plate_200_direct", 200, "direct")}`],
];

// [bundle label, its address]
const bundles = [["this", url]];
if (process.env.CDCA_OLD_URL) bundles.push(["old", process.env.CDCA_OLD_URL]);
const rows = ["bundle,scene,start,first_frame_ms,field_ms"];
const summary = [];
const browser = await launch();
try {
    for (const [scene, id, hash] of scenes) {
        const times = new Map(bundles.map(([b]) => [b, { frames: [], fields: [] }]));
        for (let i = 1; i <= starts; i++) {
            for (const [bundle, address] of bundles) {
                const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
                watch(page, `[${bundle}: ${scene} #${i}] `, { quiet: true });
                try {
                    await open(page, address, hash);
                    await page.waitForFunction(() => window.cdcaState?.firstFieldMs != null, null, {
                        timeout: START_TIMEOUT_MS,
                        polling: 50,
                    });
                    const s = await page.evaluate(() => window.cdcaState);
                    times.get(bundle).frames.push(s.firstFrameMs);
                    times.get(bundle).fields.push(s.firstFieldMs);
                    rows.push(`${bundle},${id},${i},${s.firstFrameMs.toFixed(0)},${s.firstFieldMs.toFixed(0)}`);
                    log(
                        `${bundle}: ${scene} #${i}: first frame ${s.firstFrameMs.toFixed(0)} ms, ` +
                            `field ${s.firstFieldMs.toFixed(0)} ms`,
                    );
                } catch (e) {
                    problems.push(`${bundle}: ${scene} #${i}: ${e.message}`);
                } finally {
                    await page.context().close();
                }
            }
        }
        for (const [bundle] of bundles) {
            const { frames, fields } = times.get(bundle);
            if (frames.length) {
                const label = bundles.length > 1 ? `${scene}, ${bundle} bundle` : scene;
                summary.push([label, frames.length, medianMax(frames), medianMax(fields)]);
            }
        }
        if (bundles.length > 1 && summary.length >= 2) {
            const [a, b] = summary.slice(-2);
            const d = (x, y) => `${x.median - y.median >= 0 ? "+" : ""}${((x.median - y.median) / 1000).toFixed(2)} s`;
            log(`${scene}: this bundle against the old: first frame ${d(a[2], b[2])}, first field ${d(a[3], b[3])}`);
            summary.push([`${scene}: this − old`, "", a[2].median - b[2].median, a[3].median - b[3].median]);
        }
    }
} finally {
    await browser.close();
}
writeFileSync(outPath, rows.join("\n") + "\n");

const s = (ms) => `${(ms / 1000).toFixed(2)} s`;
console.log("\n| scene | starts | first frame, median | max | first field, median | max |");
console.log("| --- | --- | --- | --- | --- | --- |");
for (const [scene, n, f, g] of summary) {
    if (typeof f === "number") {
        console.log(`| ${scene} | | ${s(f)} | | ${s(g)} | |`);
    } else {
        console.log(`| ${scene} | ${n} | ${s(f.median)} | ${s(f.max)} | ${s(g.median)} | ${s(g.max)} |`);
    }
}
if (problems.length) {
    console.error(`\nfirst frame FAILED (${problems.length} problem(s)):`);
    for (const p of problems) console.error(`  - ${p}`);
    process.exit(1);
}
