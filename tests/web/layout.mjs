// The workbench's layout in the browser (issue 56, "Must show"), at a
// laptop's 1280 × 800, a classroom projector's 1024 × 640 and a phone's
// 390 × 844: each after a fresh load at that size and after a resize to
// it (loaded at 1280 × 800, or 1024 × 640 for 1280 × 800 itself). Asserts
// from the app's own rectangles (window.cdcaWidgets, window.cdcaState:
// src/app/web.rs), as tests/ui_layout.rs does natively:
//   - at 1024 × 640 the specimen spans at least half the window's height;
//   - at 390 × 844 the canvas and the Run growth button are on screen;
//   - at every size, no key on the canvas (the key, the colour legend, the
//     load labels) overlaps another, and each lies inside the canvas;
//   - after Run growth on the default scene, loaded at each size (issue
//     65, as tests/ui_sizes.rs natively): the story whole in the window and
//     off the canvas, and the plot (the tab the run ends on) whole in the
//     window and at least 180 px tall.
// Saves a screenshot of each case as OUTDIR/web-layout-WxH.png,
// OUTDIR/web-layout-WxH-after-resize.png and OUTDIR/web-layout-WxH-after-run.png
// (docs/browser.md shows them).
//
//   node tests/web/layout.mjs URL OUTDIR
import { mkdirSync } from "node:fs";
import { START_TIMEOUT_MS, hooks, launch, log, open, problems, watch } from "./common.mjs";

// Longest Run growth of the default scene waited for, ms.
const RUN_TIMEOUT_MS = 600_000;
// Least height of the plot after a run, CSS px (= points at 100 %).
const MIN_PLOT = 180;

const [url, outDir] = process.argv.slice(2);
if (!url || !outDir) {
    console.error("usage: node layout.mjs URL OUTDIR");
    process.exit(2);
}
mkdirSync(outDir, { recursive: true });

const LAPTOP = [1280, 800];
const PROJECTOR = [1024, 640];
const PHONE = [390, 844];
const CANVAS = "Specimen canvas"; // src/canvas/mod.rs, CANVAS_LABEL

const name = ([w, h]) => `${w}×${h}`;
const show = (r) => `(${r.x.toFixed(0)}, ${r.y.toFixed(0)}) ${r.w.toFixed(0)}×${r.h.toFixed(0)}`;
// Half a pixel of rounding allowed, as natively.
const inside = (r, o) => r.x >= o.x - 0.5 && r.y >= o.y - 0.5 && r.x + r.w <= o.x + o.w + 0.5 && r.y + r.h <= o.y + o.h + 0.5;
const overlap = (a, b) => a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;

// The layout as the app last published it: the specimen, the keys drawn on
// the canvas, the canvas and the Run growth button.
const readLayout = (page) =>
    page.evaluate((labels) => {
        const widget = (label) => {
            const w = (window.cdcaWidgets || []).find((w) => w.label === label);
            return w && { x: w.x, y: w.y, w: w.w, h: w.h };
        };
        const s = window.cdcaState || {};
        return {
            specimen: s.specimen,
            keys: s.keys,
            story: s.story,
            plot: s.plot,
            canvas: widget(labels[0]),
            runGrowth: widget(labels[1]),
        };
    }, [CANVAS, "Run growth"]);

// Waits until the layout has stopped changing (two reads 300 ms apart
// agree), after a load or a resize.
async function settledLayout(page, what) {
    let last = "";
    for (let i = 0; i < 100; i++) {
        const layout = await readLayout(page);
        const now = JSON.stringify(layout);
        if (now === last && layout.canvas && layout.specimen) return layout;
        last = now;
        await page.waitForTimeout(300);
    }
    throw new Error(`${what}: the layout did not settle: ${last}`);
}

// The checks at one size; the failures name the size and the rectangles.
function check([w, h], layout, what) {
    const fail = (msg) => problems.push(`${what}: ${msg}`);
    const screen = { x: 0, y: 0, w, h };
    const { specimen, keys, canvas, runGrowth } = layout;
    if (w === PROJECTOR[0] && h === PROJECTOR[1] && specimen.h < 0.5 * h) {
        fail(`the specimen ${show(specimen)} spans ${specimen.h.toFixed(0)} px, less than half the window's ${h} px`);
    }
    if (w === PHONE[0] && h === PHONE[1]) {
        if (!inside(canvas, screen)) fail(`the canvas ${show(canvas)} is not on screen ${show(screen)}`);
        if (!runGrowth) fail("no Run growth button");
        else if (!inside(runGrowth, screen)) {
            fail(`the Run growth button ${show(runGrowth)} is not on screen ${show(screen)}`);
        }
    }
    for (const [i, a] of keys.entries()) {
        if (!inside(a, canvas)) fail(`the ${a.name} ${show(a)} is not inside the canvas ${show(canvas)}`);
        for (const b of keys.slice(i + 1)) {
            if (overlap(a, b)) fail(`the ${a.name} ${show(a)} overlaps the ${b.name} ${show(b)}`);
        }
    }
    log(
        `${what}: specimen ${show(specimen)} (${((100 * specimen.h) / h).toFixed(0)}% of the height), ` +
            `canvas ${show(canvas)}, Run growth ${runGrowth ? show(runGrowth) : "none"}; ` +
            `keys ${keys.map((k) => `${k.name} ${show(k)}`).join(", ")}`,
    );
}

// After a run: the story and the plot whole on screen, the story off the
// canvas, the plot at least MIN_PLOT tall.
function checkAfterRun([w, h], layout, what) {
    const fail = (msg) => problems.push(`${what}: ${msg}`);
    const screen = { x: 0, y: 0, w, h };
    const { story, plot, canvas } = layout;
    if (!story) fail("no story after the run");
    else {
        if (!inside(story, screen)) fail(`the story ${show(story)} is not on screen ${show(screen)}`);
        if (overlap(story, canvas)) fail(`the story ${show(story)} overlaps the canvas ${show(canvas)}`);
    }
    if (!plot) fail("no plot after the run");
    else {
        if (!inside(plot, screen)) fail(`the plot ${show(plot)} is not on screen ${show(screen)}`);
        if (plot.h < MIN_PLOT - 0.5) fail(`the plot ${show(plot)} is ${plot.h.toFixed(0)} px tall, under ${MIN_PLOT}`);
    }
    log(`${what}: story ${story ? show(story) : "none"}, plot ${plot ? show(plot) : "none"}, canvas ${show(canvas)}`);
}

const browser = await launch();
try {
    for (const size of [LAPTOP, PROJECTOR, PHONE]) {
        const from = size === LAPTOP ? PROJECTOR : LAPTOP;
        for (const resized of [false, true]) {
            const what = resized ? `${name(from)} resized to ${name(size)}` : `${name(size)} loaded`;
            const start = resized ? from : size;
            const page = await browser.newPage({ viewport: { width: start[0], height: start[1] } });
            watch(page, `[${what}] `, { quiet: true });
            try {
                await open(page, url);
                const { waitState } = hooks(page);
                await waitState(
                    () => window.cdcaState?.solved && window.cdcaState.fieldShown,
                    `${what}: the default scene solved and its field shown`,
                    START_TIMEOUT_MS,
                );
                if (resized) {
                    await settledLayout(page, `${what}, before the resize`);
                    await page.setViewportSize({ width: size[0], height: size[1] });
                }
                const layout = await settledLayout(page, what);
                check(size, layout, what);
                const shot = `${outDir}/web-layout-${size[0]}x${size[1]}${resized ? "-after-resize" : ""}.png`;
                await page.screenshot({ path: shot });
                log(`screenshot: ${shot}`);
                if (!resized) {
                    const { click } = hooks(page);
                    await click("Run growth");
                    await waitState(
                        () => window.cdcaState?.outcome && window.cdcaState.runMode === "Paused",
                        `${what}: Run growth ends`,
                        RUN_TIMEOUT_MS,
                    );
                    const ran = `${what}, after Run growth`;
                    const after = await settledLayout(page, ran);
                    checkAfterRun(size, after, ran);
                    const runShot = `${outDir}/web-layout-${size[0]}x${size[1]}-after-run.png`;
                    await page.screenshot({ path: runShot });
                    log(`screenshot: ${runShot}`);
                }
            } catch (e) {
                problems.push(`${what}: ${e.message}`);
            } finally {
                await page.context().close();
            }
        }
    }
} finally {
    await browser.close();
}

if (problems.length) {
    console.error(`\nlayout FAILED (${problems.length} problem(s)):`);
    for (const p of problems) console.error(`  - ${p}`);
    process.exit(1);
}
console.log("\nlayout OK");
