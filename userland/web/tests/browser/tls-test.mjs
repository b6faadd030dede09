// SPDX-License-Identifier: GPL-2.0
// The dashboard over HTTPS and WSS in a real browser: advee-web started with
// --tls-cert and --tls-key (browser-check.sh makes a throw-away self-signed
// certificate for the run and starts it). Chromium trusts that one
// certificate only: --ignore-certificate-errors-spki-list with its public
// key's hash, not --ignore-certificate-errors. One login + drive with the
// keys, what reaches LCM read by advee-stack-listen; then a Chromium without
// the hash must be refused the page.
//   node tls-test.mjs   (environment: WEB_URL (https://), SPKI, LISTEN,
//                        CHROMIUM, OP1, PW1)
// Output as dashboard-test.mjs: "ROW<TAB>ok|fail<TAB>name<TAB>note",
// "FIGURE<TAB>name<TAB>value".
import {spawn} from "node:child_process";
import puppeteer from "puppeteer-core";

const env = (k) => {
  if (!process.env[k]) throw new Error(`${k} not set`);
  return process.env[k];
};
const URL0 = env("WEB_URL"), OP1 = env("OP1"), PW1 = env("PW1");
const RELEASE_LIMIT_MS = 100;
let failed = 0;
const row = (ok, name, note = "") => {
  if (!ok) failed++;
  console.log(`ROW\t${ok ? "ok" : "fail"}\t${name}\t${note}`);
};
const figure = (name, value) => console.log(`FIGURE\t${name}\t${value}`);
const monoS = () => Number(process.hrtime.bigint()) / 1e9;
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// LCM through advee-stack-listen (as dashboard-test.mjs).
const lcm = [];
const listener = spawn(env("LISTEN"), ["--stamps", "--seconds", "120", "LL_CMD_MOTION"],
                       {stdio: ["ignore", "pipe", "inherit"]});
let partial = "";
listener.stdout.on("data", (d) => {
  const lines = (partial + d).split("\n");
  partial = lines.pop();
  for (const l of lines) {
    const [ch, ...kv] = l.split(" ");
    const m = {ch, line: l};
    for (const p of kv) {
      const i = p.indexOf("=");
      if (i > 0) m[p.slice(0, i)] = p.slice(i + 1);
    }
    m.t = Number(m.t);
    lcm.push(m);
  }
});
const motions = (since) => lcm.filter((m) => m.t >= since && m.ch === "LL_CMD_MOTION" && m.module === "advee-web");
const isStop = (m) => Number(m.speed) === 0 && Number(m.steering) === 0;
async function waitStop(since, ms = 3000) {
  const end = Date.now() + ms;
  for (;;) {
    const hit = motions(since).find(isStop);
    if (hit || Date.now() > end) return hit;
    await sleep(5);
  }
}

async function main() {
  const browser = await puppeteer.launch({
    executablePath: env("CHROMIUM"), headless: true,
    args: ["--no-sandbox", "--disable-gpu", "--hide-scrollbars", `--ignore-certificate-errors-spki-list=${env("SPKI")}`],
    defaultViewport: {width: 1400, height: 900}});
  try {
    const page = await browser.newPage();
    page.setDefaultTimeout(10000);
    // The key's release time on the wall clock, as dashboard-test.mjs: the
    // limit is asserted from the page's own event (a loaded machine delays
    // the browser's input dispatch, which is not the bridge's).
    await page.evaluateOnNewDocument(() => {
      window.addEventListener("keyup", (e) => { window.keyup = performance.timeOrigin + e.timeStamp; }, true);
    });
    await page.goto(URL0, {waitUntil: "load"});
    const connected = await page.waitForFunction(
      () => document.getElementById("conn-status").textContent === "connected").then(() => true, () => false);
    row(connected && await page.evaluate(() => location.protocol) === "https:",
        "https: the page loads and its WebSocket (wss) connects");
    await page.type("#login-user", OP1);
    await page.type("#login-password", PW1);
    await page.click("#login");
    await page.waitForFunction((u) => document.getElementById("operator").textContent === u, {}, OP1);
    await page.waitForFunction(() => document.getElementById("conn-status").textContent === "connected" &&
                                     !document.getElementById("take").hidden);
    const cookie = (await page.cookies()).find((c) => c.name === "advee_session");
    row(cookie && cookie.secure && cookie.httpOnly && cookie.sameSite === "Strict",
        "https: login, the session cookie Secure (without --secure-cookie), HttpOnly, SameSite=Strict",
        cookie ? `secure=${cookie.secure} httpOnly=${cookie.httpOnly} sameSite=${cookie.sameSite}` : "no cookie");
    await page.click("#take");
    await page.waitForFunction(() => document.getElementById("lease").textContent === "you have control");
    const t0 = monoS();
    await page.keyboard.down("ArrowUp");
    await sleep(500);
    const drove = motions(t0).filter((m) => !isStop(m));
    row(drove.length >= 2 && Math.abs(Number(drove[0].speed) - 0.5) < 0.002 && Number(drove[0].steering) === 0,
        `https: the up key drives over wss, LL_CMD_MOTION 0.50 m/s (${drove.length} in 0.5 s)`,
        drove[0] ? drove[0].line : "none");
    const tr = monoS();
    await page.keyboard.up("ArrowUp");
    const stop = await waitStop(tr);
    const sent = stop ? (stop.t - tr) * 1000 : Infinity;
    const up = await page.evaluate(() => window.keyup);
    const ev = stop && up ? Number(stop.rx_us) / 1000 - up : Infinity;
    figure("https: key release event to stop on LCM (ms)", ev.toFixed(1));
    figure("https: key input sent to the browser to stop on LCM (ms)", sent.toFixed(1));
    row(ev <= RELEASE_LIMIT_MS, `https: key release, zero command ${ev.toFixed(1)} ms after the release event ` +
        `(${sent.toFixed(1)} ms after the input was sent; limit ${RELEASE_LIMIT_MS})`);
  } finally {
    await browser.close();
  }
}

// Without the certificate's key hash the same Chromium refuses the page: the
// trust above is that one certificate, and the server's is really checked.
async function untrusted() {
  const browser = await puppeteer.launch({executablePath: env("CHROMIUM"), headless: true,
                                          args: ["--no-sandbox", "--disable-gpu"]});
  try {
    const page = await browser.newPage();
    const err = await page.goto(URL0, {waitUntil: "load", timeout: 10000}).then(() => "loaded", (e) => String(e));
    row(/ERR_CERT_/.test(err), "https: a browser that does not trust the certificate gets no page",
        err.split("\n")[0]);
  } finally {
    await browser.close();
  }
}

try {
  await main();
  await untrusted();
} catch (e) {
  row(false, "https browser test ran to the end", String(e.stack || e).split("\n").slice(0, 3).join(" | "));
}
listener.kill();
process.exit(failed ? 1 : 0);
