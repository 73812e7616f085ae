// A link after a run shares the scene as drawn (issue 66, "Must show"):
// on the default scene, Run growth to its end, then File ▸ Copy link to
// this scene. The page address then holds `#scene=…`; a new page opened on
// it shows the drawn scene (the same name and crack points as a fresh
// page, no growth step), not the run's grown cracks. Reset on the first
// page takes the link out of its address. Asserts from the app's own
// state (window.cdcaState, src/app/web.rs).
//
//   node tests/web/link.mjs URL
import { START_TIMEOUT_MS, hooks, launch, log, open, problems, watch } from "./common.mjs";

const [url] = process.argv.slice(2);
if (!url) {
    console.error("usage: node link.mjs URL");
    process.exit(2);
}

// Longest Run growth of the default scene waited for, ms.
const RUN_TIMEOUT_MS = 600_000;

const solved = () => window.cdcaState?.solved && window.cdcaState.fieldShown && window.cdcaState.runMode === "Paused";

const browser = await launch();
try {
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    watch(page, "[run] ", { quiet: true });
    await open(page, url);
    const { state, waitState, click } = hooks(page);
    await waitState(solved, "the default scene solved", START_TIMEOUT_MS);
    const drawn = await state();
    await click("Run growth");
    await waitState(() => window.cdcaState?.outcome && window.cdcaState.runMode === "Paused", "Run growth ends", RUN_TIMEOUT_MS);
    const ran = await state();
    log(`after the run: ${ran.growthSteps} steps, ${ran.crackPoints} crack points (drawn: ${drawn.crackPoints})`);
    if (!(ran.growthSteps > 0 && ran.crackPoints > drawn.crackPoints)) {
        problems.push(`the run grew nothing to tell apart: ${JSON.stringify(ran)}`);
    }
    await click("File");
    await click("Copy link to this scene");
    await waitState(() => window.location.hash.startsWith("#scene="), "the address holds the link");
    const hash = await page.evaluate(() => window.location.hash);
    log(`link: ${hash.length} characters`);

    const shared = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    watch(shared, "[shared] ", { quiet: true });
    await open(shared, url, hash);
    const h2 = hooks(shared);
    await h2.waitState(solved, "the linked scene solved", START_TIMEOUT_MS);
    const opened = await h2.state();
    log(`the link opens: "${opened.sceneName}", ${opened.growthSteps} steps, ${opened.crackPoints} crack points`);
    if (opened.sceneName !== drawn.sceneName) problems.push(`the link opens "${opened.sceneName}", not "${drawn.sceneName}"`);
    if (opened.growthSteps !== 0) problems.push(`the link opens a run of ${opened.growthSteps} steps`);
    if (opened.crackPoints !== drawn.crackPoints) {
        problems.push(`the link opens ${opened.crackPoints} crack points, the drawn scene has ${drawn.crackPoints} (the run ${ran.crackPoints})`);
    }
    await shared.close();

    await click("Reset");
    await waitState(() => !window.location.hash.startsWith("#scene="), "Reset takes the link out of the address");
    log(`after Reset the address's fragment is "${await page.evaluate(() => window.location.hash)}"`);
    await page.close();
} catch (e) {
    problems.push(e.message);
} finally {
    await browser.close();
}

if (problems.length) {
    console.error(`\nlink FAILED (${problems.length} problem(s)):`);
    for (const p of problems) console.error(`  - ${p}`);
    process.exit(1);
}
console.log("\nlink OK");
