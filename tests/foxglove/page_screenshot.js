// Loads mrsim-foxglove's browser page in headless Chromium, waits until the
// page says it has drawn the robots ("mrsim: live" in its title), and
// saves a screenshot. Drives Chromium over its DevTools protocol with `ws`
// (the package of package-lock.json), so it waits for the page itself,
// never for a fixed time.
//
//   node page_screenshot.js CHROMIUM URL OUT.png [WIDTHxHEIGHT]
// Prints one JSON line (title, the page's sim time and real-time factor
// texts, the service message after pressing Pause when PRESS=pause);
// exits 0 once the screenshot is written, 1 (saying why) otherwise.
// MIN_PLOT_SPAN=S: also wait until the plot shows S sim seconds.
"use strict";
const { spawn } = require("child_process");
const fs = require("fs");
const http = require("http");
const os = require("os");
const path = require("path");
const WebSocket = require("ws");

const [chromium, url, out, size = "1000x700"] = process.argv.slice(2);
const kDeadlineMs = 90000;
const [width, height] = size.split("x").map(Number);
const profile = fs.mkdtempSync(path.join(os.tmpdir(), "mrsim-page-"));
const seen = {};

const browser = spawn(chromium, [
  "--headless=new", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
  "--use-angle=swiftshader", "--no-first-run", "--no-default-browser-check",
  "--disable-extensions", "--hide-scrollbars", "--force-device-scale-factor=1",
  `--window-size=${width},${height}`, `--user-data-dir=${profile}`,
  "--remote-debugging-port=0", "about:blank"], { stdio: ["ignore", "ignore", "pipe"] });
let browserLog = "";

let finished = false;
function finish(ok, why) {
  if (finished) return;
  finished = true;
  seen.ok = ok;
  if (why) seen.why = why;
  if (!ok && browserLog) seen.chromium = browserLog.slice(-2000);
  console.log(JSON.stringify(seen));
  // The profile goes once Chromium has stopped writing to it.
  const done = () => {
    try { fs.rmSync(profile, { recursive: true, force: true, maxRetries: 5 }); } catch { /* a temp dir */ }
    process.exit(ok ? 0 : 1);
  };
  if (browser.exitCode !== null || browser.signalCode !== null) done();
  else { browser.once("exit", done); browser.kill("SIGKILL"); }
}
setTimeout(() => finish(false, "deadline passed"), kDeadlineMs).unref();
browser.on("exit", (code) => finish(false, `chromium exited (${code})`));

// Chromium prints where its DevTools endpoint listens on stderr.
browser.stderr.on("data", (chunk) => {
  browserLog += chunk.toString();
  const m = /DevTools listening on (ws:\/\/\S+)/.exec(browserLog);
  if (m && !seen.devtools) {
    seen.devtools = true;
    const port = new URL(m[1]).port;
    http.get(`http://127.0.0.1:${port}/json/list`, (res) => {
      let body = "";
      res.on("data", (d) => (body += d));
      res.on("end", () => {
        const page = JSON.parse(body).find((t) => t.type === "page");
        if (!page) finish(false, "no page target");
        else drive(page.webSocketDebuggerUrl).catch((e) => finish(false, String(e)));
      });
    }).on("error", (e) => finish(false, String(e)));
  }
});

async function drive(target) {
  const ws = new WebSocket(target, { perMessageDeflate: false });
  await new Promise((ok, fail) => { ws.once("open", ok); ws.once("error", fail); });
  let next = 1;
  const waiting = new Map();
  const consoleLines = [];
  ws.on("message", (data) => {
    const m = JSON.parse(data);
    if (m.id && waiting.has(m.id)) {
      waiting.get(m.id)(m);
      waiting.delete(m.id);
    } else if (m.method === "Runtime.exceptionThrown") {
      consoleLines.push(m.params.exceptionDetails?.exception?.description ?? "exception");
    } else if (m.method === "Runtime.consoleAPICalled" && consoleLines.length < 20) {
      consoleLines.push(m.params.args.map((a) => a.value ?? a.description).join(" "));
    }
  });
  const send = (method, params = {}) => new Promise((ok, fail) => {
    const id = next++;
    waiting.set(id, (m) => (m.error ? fail(new Error(`${method}: ${m.error.message}`)) : ok(m.result)));
    ws.send(JSON.stringify({ id, method, params }));
  });
  const evaluate = async (expression) =>
    (await send("Runtime.evaluate", { expression, returnByValue: true })).result.value;
  // Resolves when `expression` is true; polls the page (not a sleep the
  // result depends on: the deadline is the only limit).
  const until = (expression) => new Promise((ok) => {
    const poll = async () => {
      if (await evaluate(expression)) ok();
      else setTimeout(poll, 100);
    };
    poll();
  });
  await send("Runtime.enable");
  await send("Page.enable");
  await send("Emulation.setDeviceMetricsOverride",
             { width, height, deviceScaleFactor: 1, mobile: false });
  await send("Page.navigate", { url });
  const timer = setTimeout(() => {
    seen.console = consoleLines;
    evaluate("document.title").then((t) => finish(false, `the page never said live (title "${t}")`));
  }, kDeadlineMs - 10000);
  await until("document.title === 'mrsim: live' && document.getElementById('rtf').textContent !== '–'" +
              " && document.getElementById('value').textContent !== ''");
  if (process.env.MIN_PLOT_SPAN) {  // for pictures: a plot of some length
    await until(`Number(document.getElementById('plot').dataset.span) >= ${Number(process.env.MIN_PLOT_SPAN)}`);
  }
  if (process.env.PRESS) {
    await evaluate(`document.getElementById('${process.env.PRESS}').click()`);
    await until("!/sent|^$/.test(document.getElementById('message').textContent)");
    seen.message = await evaluate("document.getElementById('message').textContent");
  }
  clearTimeout(timer);
  seen.title = await evaluate("document.title");
  seen.simtime = await evaluate("document.getElementById('simtime').textContent");
  seen.rtf = await evaluate("document.getElementById('rtf').textContent");
  seen.follow = await evaluate("document.getElementById('follow').value");
  seen.console = consoleLines;
  // One more frame, so the shot has the latest pose and plot.
  await evaluate("new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))");
  const shot = await send("Page.captureScreenshot", { format: "png" });
  fs.writeFileSync(out, Buffer.from(shot.data, "base64"));
  finish(true);
}
