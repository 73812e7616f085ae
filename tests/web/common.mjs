// What the browser tests share (smoke.mjs, layout.mjs, first_frame.mjs,
// solver_time.mjs): Debian's chromium started by playwright-core, the
// console watched for errors and the app's timing lines, the app opened
// with its test hooks, and clicks by label.
//
// The page is opened with `?cdca_test`, which makes the app publish its
// widgets (label and rectangle, from egui's AccessKit tree) as
// `window.cdcaWidgets` and its state as `window.cdcaState` (src/app/web.rs).
import { chromium } from "playwright-core";
import { readFileSync } from "node:fs";
import { deflateRawSync } from "node:zlib";

export const START_TIMEOUT_MS = 180_000;
export const STEP_TIMEOUT_MS = 60_000;

/// Problems found (console errors, panics, failed checks): the script
/// fails at the end if there is any.
export const problems = [];
/// The app's timing lines (console `timing: …`), tagged by page.
export const timings = [];
const t0 = Date.now();
export const elapsed = () => `${((Date.now() - t0) / 1000).toFixed(1)} s`;
export const log = (msg) => console.log(`[${elapsed()}] ${msg}`);

// playwright gives the browser a new temporary profile of its own.
export function launch() {
    return chromium.launch({
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
}

// Console messages of a page: the app's timing lines are kept, everything
// else is printed (unless `quiet`); errors and panic messages are problems.
export function watch(page, tag = "", { quiet = false } = {}) {
    page.on("console", (msg) => {
        const text = msg.text();
        if (text.startsWith("timing:") || text.includes(" timing: ")) {
            timings.push(`[${elapsed()}] ${tag}${text}`);
        } else if (!quiet) {
            log(`${tag}console.${msg.type()}: ${text.split("\n")[0]}`);
        }
        if (msg.type() === "error" || /panick?ed|\bpanic\b/i.test(text)) {
            problems.push(`${tag}console.${msg.type()}: ${text}`);
        }
    });
    page.on("pageerror", (e) => problems.push(`${tag}page error: ${e.message}`));
    page.on("requestfailed", (r) => problems.push(`${tag}request failed: ${r.url()} ${r.failure()?.errorText}`));
}

// Opens the app at `url` with its test hooks (`?cdca_test`) and waits until
// it has started.
export async function open(page, url, hash = "") {
    const sep = url.includes("?") ? "&" : "?";
    log(`open ${url}${sep}cdca_test${hash.slice(0, 40)}${hash.length > 40 ? "…" : ""}`);
    await page.goto(`${url}${sep}cdca_test${hash}`);
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
}

// The app's state (src/app/web.rs), waiting on it, and clicks by label.
export function hooks(page) {
    const state = () => page.evaluate(() => window.cdcaState);
    const waitState = (pred, what, timeout = STEP_TIMEOUT_MS, arg = null) =>
        page
            .waitForFunction(pred, arg, { timeout, polling: 100 })
            .catch(async (e) => {
                throw new Error(`${what}: ${e.message}; state ${JSON.stringify(await state())}`);
            });

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
    // Moves the pointer off the buttons (to the viewport's bottom-right
    // corner) so no tooltip covers a screenshot.
    const park = () => {
        const { width, height } = page.viewportSize();
        return page.mouse.move(width - 2, height - 2);
    };
    return { state, waitState, click, park };
}

// A bundled scene (assets/scenes/FILE) as a shared link's fragment,
// `scene=…` (raw deflate, base64url: what File ▸ Copy link to this scene
// writes, src/files/link.rs), with `edit` applied to the scene first.
export function sceneLink(file, edit = (s) => s) {
    const path = new URL(`../../assets/scenes/${file}`, import.meta.url);
    const scene = edit(JSON.parse(readFileSync(path, "utf8")));
    return "scene=" + deflateRawSync(Buffer.from(JSON.stringify(scene))).toString("base64url");
}

// Median and largest of a list of numbers.
export function medianMax(values) {
    const v = [...values].sort((a, b) => a - b);
    const n = v.length;
    const median = n % 2 ? v[(n - 1) / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
    return { median, max: v[n - 1] };
}
