// Opens brdf report pages in a real browser (Debian's chromium, headless,
// through playwright-core) and checks them: no console errors, no network
// requests (the pages are self-contained), every image decoded with a
// non-zero size, every section present, the index sorts when a header is
// clicked, every link of the index loads. A screenshot of each page goes
// into OUT_DIR.
//
// usage: node check.js OUT_DIR FIT_PAGE.html BATCH_INDEX.html
"use strict";
const path = require("path");
const { pathToFileURL } = require("url");
const { chromium } = require("playwright-core");

const [outDir, fitPage, indexPage] = process.argv.slice(2);
if (!indexPage) {
  console.error("usage: node check.js OUT_DIR FIT_PAGE.html BATCH_INDEX.html");
  process.exit(2);
}
let passed = 0;
let failed = 0;
function check(ok, what) {
  if (ok) {
    passed += 1;
    console.log(`ok: ${what}`);
  } else {
    failed += 1;
    console.log(`FAILED: ${what}`);
  }
}

// A page opened with its console errors and outside requests recorded.
async function open(browser, file) {
  const page = await browser.newPage({ viewport: { width: 1450, height: 900 } });
  const problems = [];
  page.on("console", (m) => m.type() === "error" && problems.push(`console: ${m.text()}`));
  page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
  page.on("request", (r) => {
    const u = r.url();
    if (!u.startsWith("file:") && !u.startsWith("data:")) problems.push(`network request: ${u}`);
  });
  const url = file.startsWith("file:") ? file : pathToFileURL(path.resolve(file)).href;
  const response = await page.goto(url, { waitUntil: "load" });
  return { page, problems, response };
}

async function imagesDecoded(page) {
  return page.evaluate(async () => {
    const imgs = Array.from(document.images);
    await Promise.all(imgs.map((i) => i.decode().catch(() => null)));
    return { count: imgs.length, bad: imgs.filter((i) => !(i.naturalWidth > 0)).map((i) => i.alt) };
  });
}

async function checkPage(browser, file, name, sections) {
  const { page, problems } = await open(browser, file);
  const imgs = await imagesDecoded(page);
  check(imgs.count > 0 && imgs.bad.length === 0, `${name}: ${imgs.count} images decoded (bad: ${imgs.bad.join(", ") || "none"})`);
  for (const id of sections) {
    check((await page.locator(`#${id}`).count()) === 1, `${name}: section #${id} present`);
  }
  check(problems.length === 0, `${name}: no console errors or requests (${problems.join("; ") || "none"})`);
  await page.screenshot({ path: path.join(outDir, `${name}.png`), fullPage: true });
  return page;
}

async function columnValues(page, col) {
  return page.$$eval(`#fits tbody tr`, (rows, c) =>
    rows.map((r) => r.children[c].dataset.value ?? r.children[c].textContent.trim()), col);
}

async function checkSort(page) {
  const headers = await page.$$eval("#fits th", (ths) => ths.map((t) => t.textContent.trim()));
  const col = headers.indexOf("Ngan L2");
  check(col >= 0, "index: has an Ngan L2 column");
  await page.click(`#fits th:nth-child(${col + 1})`);
  const up = (await columnValues(page, col)).map(Number);
  check(up.every((v, k) => k === 0 || up[k - 1] <= v), `index: ascending after one click (${up.join(", ")})`);
  await page.click(`#fits th:nth-child(${col + 1})`);
  const down = (await columnValues(page, col)).map(Number);
  check(down.every((v, k) => k === 0 || down[k - 1] >= v), `index: descending after two clicks (${down.join(", ")})`);
  const mcol = headers.indexOf("model");
  await page.click(`#fits th:nth-child(${mcol + 1})`);
  const models = await columnValues(page, mcol);
  check(models.every((v, k) => k === 0 || models[k - 1] <= v), `index: models sorted (${models.join(", ")})`);
}

async function checkLinks(browser, page) {
  const links = await page.$$eval("#fits a[href]", (as) => as.map((a) => a.href));
  check(links.length > 0, `index: ${links.length} links to fit pages`);
  for (const [k, href] of links.entries()) {
    const { page: p, problems, response } = await open(browser, href);
    const title = await p.locator("h1").count();
    const imgs = await imagesDecoded(p);
    check((response === null || response.ok()) && title === 1, `link loads: ${href}`);
    check(imgs.bad.length === 0 && problems.length === 0, `linked page clean: ${href}`);
    if (k === 0) await p.screenshot({ path: path.join(outDir, "batch-fit.png"), fullPage: true });
    await p.close();
  }
}

// The part people look at comes first: the measured, fitted and FLIP
// spheres and the verdict sit in the first screen, above the parameters.
async function checkSpheresFirst(page) {
  const top = (sel) => page.locator(sel).first().evaluate((e) => e.getBoundingClientRect().top + window.scrollY);
  const spheres = await top("#spheres img.sphere");
  const verdict = await top("#verdict");
  const params = await top("#params");
  check(spheres < 900 && spheres < params && verdict < params,
    `fit: spheres (${spheres.toFixed(0)} px) and verdict (${verdict.toFixed(0)} px) above the parameters (${params.toFixed(0)} px), the spheres in the first screen`);
}

(async () => {
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
      "--disable-component-update", "--disable-sync", "--no-first-run"],
  });
  try {
    const fitSections = ["summary", "verdict", "params", "slices", "coverage", "spheres", "errors"];
    const fit = await checkPage(browser, fitPage, "fit", fitSections);
    await checkSpheresFirst(fit);
    await fit.close();
    const index = await checkPage(browser, indexPage, "batch-index", ["fits"]);
    await checkSort(index);
    await checkLinks(browser, index);
  } finally {
    await browser.close();
  }
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed === 0 ? 0 : 1);
})().catch((e) => {
  console.error(`browser test: ${e.message}`);
  process.exit(1);
});
