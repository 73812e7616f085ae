// Browser test of the WebAssembly build: opens the served dist/ in headless
// Chromium (Debian's, driven by playwright-core), waits until the default
// scene is solved and its stress field drawn, clicks Step, "Grow one step"
// (three times) and Solve by their labels, checks the app's state after each click,
// turns on the frame-time overlay and saves a screenshot; then saves the
// scene and the crack paths (downloads) and opens another scene through the
// file dialog. Fails on any console error, page error or panic message.
//
//   node tests/web/smoke.mjs URL SCREENSHOT.png [TIMINGS.txt]
//
// The page is opened with `?cdca_test`, which makes the app publish its
// widgets (label and rectangle, from egui's AccessKit tree) as
// `window.cdcaWidgets` and its state as `window.cdcaState` (src/web.rs).
import { chromium } from "playwright-core";
import { readFileSync, writeFileSync } from "node:fs";

const [url, screenshotPath, timingsPath] = process.argv.slice(2);
if (!url || !screenshotPath) {
    console.error("usage: node smoke.mjs URL SCREENSHOT.png [TIMINGS.txt]");
    process.exit(2);
}
const GROW_CLICKS = 3;
const START_TIMEOUT_MS = 180_000;
const STEP_TIMEOUT_MS = 60_000;

const problems = [];
const timings = [];
const t0 = Date.now();
const elapsed = () => `${((Date.now() - t0) / 1000).toFixed(1)} s`;
const log = (msg) => console.log(`[${elapsed()}] ${msg}`);

// playwright gives the browser a new temporary profile of its own.
const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    headless: true,
    args: [
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--enable-unsafe-swiftshader",
    ],
});

try {
    const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
    page.on("console", (msg) => {
        const text = msg.text();
        if (text.startsWith("timing:") || text.includes(" timing: ")) {
            timings.push(`[${elapsed()}] ${text}`);
        } else {
            log(`console.${msg.type()}: ${text.split("\n")[0]}`);
        }
        if (msg.type() === "error" || /panick?ed|\bpanic\b/i.test(text)) {
            problems.push(`console.${msg.type()}: ${text}`);
        }
    });
    page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
    page.on("requestfailed", (r) => problems.push(`request failed: ${r.url()} ${r.failure()?.errorText}`));

    const sep = url.includes("?") ? "&" : "?";
    log(`open ${url}${sep}cdca_test`);
    await page.goto(`${url}${sep}cdca_test`);
    await page.waitForSelector("#cdca_canvas");

    // Started, or a visible failure message?
    await page.waitForFunction(
        () => ["hidden", "error"].includes(document.getElementById("cdca_status")?.className),
        null,
        { timeout: START_TIMEOUT_MS },
    );
    const status = await page.$eval("#cdca_status", (e) => [e.className, e.textContent]);
    if (status[0] === "error") {
        throw new Error(`the page shows a start failure: ${status[1]}`);
    }
    log("app started");

    const state = () => page.evaluate(() => window.cdcaState);
    const waitState = (pred, what, timeout = STEP_TIMEOUT_MS) =>
        page
            .waitForFunction(pred, null, { timeout, polling: 100 })
            .catch(async (e) => {
                throw new Error(`${what}: ${e.message}; state ${JSON.stringify(await state())}`);
            });

    const tSolve = Date.now();
    await waitState(
        () => window.cdcaState?.solved && window.cdcaState.fieldShown,
        "the default scene is solved and its field shown",
        START_TIMEOUT_MS,
    );
    log(`solved, field shown (${Date.now() - tSolve} ms after start)`);
    const solved = await state();
    if (solved.message?.startsWith("error")) throw new Error(`app error: ${solved.message}`);
    if (!(solved.fieldFinite > 0)) throw new Error(`no stress values in the field: ${JSON.stringify(solved)}`);

    // Clicks a widget by its label, like the egui_kittest tests natively.
    async function click(label) {
        const handle = await page.waitForFunction(
            (label) => (window.cdcaWidgets || []).find((w) => w.label === label && !w.disabled),
            label,
            { timeout: STEP_TIMEOUT_MS, polling: 100 },
        );
        const w = await handle.jsonValue();
        const x = w.x + w.w / 2;
        const y = w.y + w.h / 2;
        await page.mouse.move(x, y);
        await page.mouse.down();
        await page.waitForTimeout(50);
        await page.mouse.up();
        log(`clicked "${label}" at (${x.toFixed(0)}, ${y.toFixed(0)})`);
    }
    // Moves the pointer off the buttons so no tooltip covers the screenshot.
    const park = () => page.mouse.move(1398, 898);

    const solvedShot = screenshotPath.replace(/\.png$/, "") + "-solved.png";
    await page.screenshot({ path: solvedShot });
    log(`screenshot before growth: ${solvedShot}`);

    await click("Step");
    await park();
    await waitState(
        () => window.cdcaState?.solved && window.cdcaState.runMode === "Paused",
        "solved after Step",
    );
    const afterStep = await state();
    if (afterStep.message?.startsWith("error")) throw new Error(`after Step: ${afterStep.message}`);

    const cracksBefore = afterStep.crackPoints;
    for (let i = 1; i <= GROW_CLICKS; i++) {
        const tGrow = Date.now();
        await click("Grow one step");
        await park();
        await waitState(
            (n) => window.cdcaState?.growthSteps >= n && window.cdcaState.fieldShown,
            `growth step ${i} done and its field shown`,
        );
        log(`growth step ${i}: ${Date.now() - tGrow} ms from click to field shown`);
    }
    const grown = await state();
    log(`state after growth: ${JSON.stringify(grown)}`);
    if (grown.growthSteps < GROW_CLICKS) throw new Error(`expected ${GROW_CLICKS} growth steps`);
    if (!(grown.crackPoints > cracksBefore)) {
        throw new Error(`the crack did not grow: ${cracksBefore} → ${grown.crackPoints} polyline points`);
    }
    if (grown.message?.startsWith("error")) throw new Error(`after growth: ${grown.message}`);

    // A growth step ends with the cracks extended and not yet solved (the
    // sampled field is empty): Solve shows the stress field around the
    // grown crack.
    await click("Solve");
    await park();
    await waitState(
        () => window.cdcaState?.solved && window.cdcaState.fieldShown && window.cdcaState.fieldFinite > 0,
        "the grown crack solved and its stress field shown",
    );
    log(`after Solve: ${JSON.stringify(await state())}`);

    // The frame-time overlay (View ▸ Frame-time overlay), then let the
    // frame statistics fill with a few repaints before the screenshot.
    await click("View");
    await click("Frame-time overlay");
    await page.keyboard.press("Escape");
    await park();
    for (let i = 0; i < 30; i++) {
        await page.mouse.move(1390 - (i % 2) * 4, 896);
        await page.waitForTimeout(30);
    }
    await park();
    await page.waitForTimeout(500);
    await page.screenshot({ path: screenshotPath });
    log(`screenshot: ${screenshotPath}`);

    // Saving is a download (src/io.rs): the scene as JSON, crack paths as CSV.
    async function download(label) {
        await click("File");
        const [dl] = await Promise.all([page.waitForEvent("download", { timeout: STEP_TIMEOUT_MS }), click(label)]);
        await page.keyboard.press("Escape");
        const path = await dl.path();
        const text = readFileSync(path, "utf8");
        log(`downloaded ${dl.suggestedFilename()} (${text.length} bytes)`);
        return [dl.suggestedFilename(), text];
    }
    const [sceneFile, sceneText] = await download("Save scene…");
    const saved = JSON.parse(sceneText);
    if (!sceneFile.endsWith(".json") || saved.name !== grown.sceneName || saved.mesh?.nx !== 40) {
        throw new Error(`the saved scene ${sceneFile} is not the open scene: ${sceneText.slice(0, 200)}`);
    }
    const [csvFile, csvText] = await download("Export crack paths (CSV)…");
    const csvRows = csvText.trim().split("\n").length - 1;
    if (!csvFile.endsWith(".csv") || csvRows !== grown.crackPoints) {
        throw new Error(`${csvFile}: ${csvRows} rows for ${grown.crackPoints} crack points`);
    }

    // Opening a scene: rfd's AsyncFileDialog clicks a file input (the
    // browser's file chooser) while the click's user activation lasts, or
    // else shows the input in an overlay; the file arrives a few frames later.
    const sceneToOpen = new URL("../../assets/scenes/centre_crack_tension.json", import.meta.url).pathname;
    const chooserShown = page.waitForEvent("filechooser", { timeout: 10_000 }).catch(() => null);
    await click("File");
    await click("Open scene…");
    const chooser = await chooserShown;
    if (chooser) {
        await chooser.setFiles(sceneToOpen);
        log("file chooser: picked centre_crack_tension.json");
    } else {
        await page.waitForSelector("#rfd-input", { state: "attached", timeout: STEP_TIMEOUT_MS });
        await page.setInputFiles("#rfd-input", sceneToOpen);
        log("rfd overlay: picked centre_crack_tension.json");
    }
    await waitState(
        () => /centre crack/i.test(window.cdcaState?.sceneName ?? ""),
        "the opened scene replaces the default one",
    );
    const opened = await state();
    log(`opened: ${opened.sceneName}`);
    if (opened.message?.startsWith("error")) throw new Error(`after open: ${opened.message}`);
} catch (e) {
    problems.push(`test: ${e.message}`);
} finally {
    await browser.close();
}

console.log("\n--- timings logged by the app (src/web.rs) ---");
for (const t of timings) console.log(t);
if (timingsPath) writeFileSync(timingsPath, timings.join("\n") + "\n");

if (problems.length) {
    console.error(`\nFAILED (${problems.length} problem(s)):`);
    for (const p of problems) console.error(`  - ${p}`);
    process.exit(1);
}
console.log(`\nOK in ${elapsed()}`);
