// The solver's time in the browser, to set beside `cdca grow`'s (issue 64):
// opens each scene as a shared link in a fresh page, presses Run growth,
// waits for the run's end and prints the growth steps' work (build + solve
// + evaluate seconds of their `work`, `window.cdcaState.growthWork`), their
// number and the last λ, RUNS times per scene, alternating the scenes.
// With PROFILE.json it also records Chromium's CPU profile of the first
// run of each scene and prints the functions with the most self time
// (keep the name section: a bundle bound without --remove-name-section).
//
//   node tests/web/solver_time.mjs URL [RUNS] [PROFILE.json]
//   (CDCA_SCENES: bundled scene files, comma-separated; default the
//   stepped pair and the default scene)
import { writeFileSync } from "node:fs";
import { START_TIMEOUT_MS, hooks, launch, log, open, problems, sceneLink, watch } from "./common.mjs";

const [url, runsArg, profilePath] = process.argv.slice(2);
if (!url) {
    console.error("usage: node solver_time.mjs URL [RUNS] [PROFILE.json]");
    process.exit(2);
}
const runs = Number(runsArg ?? 3);
const scenes = (process.env.CDCA_SCENES ?? "specimen_two_flaws_stepped.json,specimen_single_flaw.json").split(",");

// "_ZN4faer6sparse…17h0123456789abcdefE" → "faer::sparse::…" (legacy mangling)
function demangle(name) {
    const m = /^_ZN(.*)E$/.exec(name);
    if (!m) return name;
    const parts = [];
    let s = m[1];
    while (s.length) {
        const n = /^(\d+)/.exec(s);
        if (!n) break;
        const len = Number(n[1]);
        parts.push(s.slice(n[1].length, n[1].length + len));
        s = s.slice(n[1].length + len);
    }
    if (/^h[0-9a-f]{16}$/.test(parts.at(-1) ?? "")) parts.pop();
    return parts
        .join("::")
        .replace(/\$LT\$/g, "<")
        .replace(/\$GT\$/g, ">")
        .replace(/\$u20\$/g, " ")
        .replace(/\$C\$/g, ",")
        .replace(/\$RF\$/g, "&")
        .replace(/\$BP\$/g, "*")
        .replace(/\.\./g, "::");
}

// Self time (ms) per function of a CPU profile, largest first.
function selfTimes(profile) {
    const byId = new Map(profile.nodes.map((n) => [n.id, n]));
    const ms = new Map();
    profile.samples.forEach((id, i) => {
        const name = demangle(byId.get(id).callFrame.functionName || "(anonymous)");
        ms.set(name, (ms.get(name) ?? 0) + (profile.timeDeltas[i + 1] ?? 0) / 1000);
    });
    return [...ms].sort((a, b) => b[1] - a[1]);
}

const browser = await launch();
const profiles = {};
try {
    for (let run = 1; run <= runs; run++) {
        for (const scene of scenes) {
            const tag = `[${scene} ${run}] `;
            const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
            watch(page, tag, { quiet: true });
            await open(page, url, `#${sceneLink(scene)}`);
            const { state, waitState, click, park } = hooks(page);
            await waitState(
                () => window.cdcaState?.solved && window.cdcaState.fieldShown && window.cdcaState.runMode === "Paused",
                `${scene} solved`,
                START_TIMEOUT_MS,
            );
            const cdp = profilePath && run === 1 ? await page.context().newCDPSession(page) : null;
            if (cdp) {
                await cdp.send("Profiler.enable");
                await cdp.send("Profiler.setSamplingInterval", { interval: 200 });
                await cdp.send("Profiler.start");
            }
            const t = Date.now();
            await click("Run growth");
            await park();
            await waitState(
                () => window.cdcaState?.growthSteps > 0 && window.cdcaState.runMode === "Paused",
                `${scene}: the run ends`,
                600_000,
            );
            const wall = (Date.now() - t) / 1000;
            if (cdp) profiles[scene] = (await cdp.send("Profiler.stop")).profile;
            const s = await state();
            const [b, so, e] = s.growthWork;
            console.log(
                `${scene}\trun ${run}\tsteps ${s.growthSteps}\tλ ${s.loadFactor}\twork ${(b + so + e).toFixed(3)} s` +
                    `\tbuild ${b.toFixed(3)}\tsolve ${so.toFixed(3)}\tevaluate ${e.toFixed(3)}\twall ${wall.toFixed(1)} s`,
            );
            await page.context().close();
        }
    }
} catch (e) {
    problems.push(`test: ${e.message}`);
} finally {
    await browser.close();
}
if (profilePath) {
    writeFileSync(profilePath, JSON.stringify(profiles));
    for (const [scene, profile] of Object.entries(profiles)) {
        const top = selfTimes(profile);
        const total = top.reduce((a, [, ms]) => a + ms, 0);
        console.log(`\n${scene}: self time of the profile's ${(total / 1000).toFixed(1)} s, top 40`);
        for (const [name, ms] of top.slice(0, 40)) console.log(`${ms.toFixed(0).padStart(7)} ms  ${name.slice(0, 160)}`);
    }
}
if (problems.length) {
    console.error(`\nFAILED: ${problems.join("\n  ")}`);
    process.exit(1);
}
