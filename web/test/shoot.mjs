// Opens pages of the browser build in headless Chromium (the system's), waits until the
// page's title says `ready` or `error: …`, and saves the canvas's picture.
//
//   node shoot.mjs BASE_URL OUT_DIR QUERY...    (QUERY: "scene=dummy&step=pcf&size=320x180")
//
// A query may end in `#keys=KeyN,KeyN`: those keys are pressed on the canvas in turn once
// the first frame is there, and the window's title (winit keeps it in the canvas's `alt`)
// is read after each, with the page's note (`#error`: what a key could not do).
//
// Prints one JSON line per page: {"query", "title", "png", "ms", "titles", "notes"}; "ms" is
// the time from navigation to the first frame on the canvas.
import puppeteer from "puppeteer-core";
import { writeFileSync } from "node:fs";
import { join } from "node:path";

const [base, outDir, ...queries] = process.argv.slice(2);
const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  headless: "new",
  args: [
    "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--no-first-run", "--disable-quic", "--force-device-scale-factor=1",
  ],
});
try {
  for (const [i, whole] of queries.entries()) {
    const [query, keyPart] = whole.split("#keys=");
    const keys = keyPart ? keyPart.split(",") : [];
    const page = await browser.newPage();
    const logs = [];
    page.on("console", (m) => logs.push(m.text()));
    page.on("pageerror", (e) => logs.push(String(e)));
    const start = Date.now();
    await page.goto(`${base}/index.html?${query}`);
    let title = "";
    try {
      await page.waitForFunction(
        () => document.title === "ready" || document.title.startsWith("error"),
        { timeout: 60000, polling: 50 });
      title = await page.title();
    } catch (e) {
      title = `timeout: ${await page.title()}; ${logs.join(" | ")}`;
    }
    const ms = Date.now() - start;
    let png = null;
    if (title === "ready") {
      const data = await page.evaluate(() =>
        document.getElementById("shadowmap").toDataURL("image/png"));
      png = join(outDir, `page-${i}.png`);
      writeFileSync(png, Buffer.from(data.split(",")[1], "base64"));
    }
    const titles = [];
    const notes = [];
    if (title === "ready") {
      await page.focus("#shadowmap");
      for (const key of keys) {
        await page.keyboard.press(key);
        await new Promise((r) => setTimeout(r, 700));
        titles.push(await page.evaluate(() => document.getElementById("shadowmap").getAttribute("alt")));
        notes.push(await page.evaluate(() => document.getElementById("error").textContent));
      }
    }
    console.log(JSON.stringify({ query: whole, title, png, ms, titles, notes, logs }));
    await page.close();
  }
} finally {
  await browser.close();
}
