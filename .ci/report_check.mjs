// Loads the reproduction report in headless Chromium (Playwright) and checks what rendered.
//
// Usage: node report_check.mjs REPORT.html PIPELINE.yaml [SCREENSHOT.png]
//
// On the page the browser built: every figure stage of the pipeline is a <figure> whose
// inlined SVG has a drawn size and drawn elements; the claims table has one row per claim
// stage; the verdict line is there. From the page's own request events (not the browser's
// background traffic): no request other than the page itself. Exit 0 when all hold, 1 with
// each failure named. Needs playwright-core (npm) and Debian's chromium.
import { chromium } from "playwright-core";
import { readFileSync } from "node:fs";
import { resolve } from "node:path";

const [report, pipeline, screenshot] = process.argv.slice(2);
if (!report || !pipeline) {
  console.error("usage: node report_check.mjs REPORT.html PIPELINE.yaml [SCREENSHOT.png]");
  process.exit(2);
}

// Stage names of a kind, from the pipeline file (`  - name:` then `    kind:`).
function stages(kind) {
  const names = [];
  let name = null;
  for (const line of readFileSync(pipeline, "utf8").split("\n")) {
    let m = line.match(/^  - name: (\S+)/);
    if (m) name = m[1];
    m = line.match(/^    kind: (\S+)\s*$/);
    if (m && name && m[1] === kind) names.push(name);
  }
  return names;
}

const url = "file://" + resolve(report);
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  args: ["--no-sandbox", "--disable-gpu"],
});
const page = await browser.newPage({ viewport: { width: 1200, height: 2400 } });
const requests = [];
page.on("request", (r) => requests.push(r.url()));
await page.goto(url, { waitUntil: "load" });
const seen = await page.evaluate(() => {
  const figures = {};
  for (const f of document.querySelectorAll("figure[id^='figure-']")) {
    const svg = f.querySelector("svg");
    const box = svg ? svg.getBoundingClientRect() : { width: 0, height: 0 };
    figures[f.id.slice(7)] = {
      drawn: svg ? svg.querySelectorAll("path, line, polyline, rect, circle, text").length : 0,
      width: box.width,
      height: box.height,
    };
  }
  const claims = [...document.querySelectorAll("table.claims tr[id^='claim-']")].filter(
    (tr) => !tr.closest("figure"),
  ).length;
  const verdict = document.querySelector("#verdict")?.textContent ?? "";
  // Every id once; every claim row says what it compared; claims in the thesis' order.
  const ids = [...document.querySelectorAll("[id]")].map((e) => e.id);
  const duplicates = ids.filter((id, i) => ids.indexOf(id) !== i);
  const rows = [...document.querySelectorAll("table.claims tr[id^='claim-']")].filter((tr) => !tr.closest("figure"));
  const withoutQuantity = rows.filter((tr) => !(tr.cells[3]?.textContent ?? "").includes(" of ")).map((tr) => tr.id);
  const chapter = (id) => {
    const p = id.slice(6).split(".")[0];
    return p === "appA" ? 7 : Number(p.replace("ch", "")) || 99;
  };
  const order = rows.map((tr) => chapter(tr.id));
  const outOfOrder = order.some((c, i) => i > 0 && c < order[i - 1]);
  // The stage graph: a panel per chapter, every arrow it declares drawn with its head.
  const graphs = [...document.querySelectorAll("svg.graph")].map((g) => ({
    declared: Number(g.dataset.edges),
    drawn: [...g.querySelectorAll("path.edge[marker-end]")].filter((e) => {
      const b = e.getBBox();
      return b.width > 0 || b.height > 0;
    }).length,
  }));
  return { figures, claims, verdict, duplicates, withoutQuantity, outOfOrder, graphs };
});
if (screenshot) await page.screenshot({ path: screenshot });
await browser.close();

const failures = [];
const figures = stages("figure");
for (const f of figures) {
  const s = seen.figures[f];
  if (!s) failures.push(`figure ${f}: not in the page`);
  else if (s.drawn < 5 || s.width < 100 || s.height < 100)
    failures.push(`figure ${f}: ${s.drawn} drawn elements, ${s.width} x ${s.height} px`);
}
const claims = stages("claim");
if (seen.claims !== claims.length) failures.push(`claims table: ${seen.claims} rows for ${claims.length} claim stages`);
if (!/thesis claims reproduced/.test(seen.verdict)) failures.push(`verdict line: ${JSON.stringify(seen.verdict)}`);
if (seen.duplicates.length) failures.push(`ids given twice: ${[...new Set(seen.duplicates)].slice(0, 5).join(", ")}`);
if (seen.withoutQuantity.length) failures.push(`claims without the quantity compared: ${seen.withoutQuantity.slice(0, 5).join(", ")}`);
if (seen.outOfOrder) failures.push("claims not in the thesis' chapter order");
const arrows = seen.graphs.reduce((n, g) => n + g.drawn, 0);
if (seen.graphs.length < 2) failures.push(`stage graph: ${seen.graphs.length} panel(s)`);
if (arrows === 0 || seen.graphs.some((g) => g.drawn !== g.declared))
  failures.push(`stage graph: arrows drawn ${JSON.stringify(seen.graphs)}`);
const left = requests.filter((u) => u !== url);
if (left.length) failures.push(`requests left the page: ${left.slice(0, 5).join(", ")}`);
console.log(
  `report_check: ${Object.keys(seen.figures).length} figures rendered (pipeline: ${figures.length}), ` +
    `${seen.claims} claims (pipeline: ${claims.length}), ${left.length} request(s) beyond the page, ` +
    `${seen.duplicates.length} repeated id(s), ${seen.graphs.length} graph panels with ${arrows} arrows; ${seen.verdict}`,
);
for (const f of failures) console.log("FAIL " + f);
process.exit(failures.length ? 1 : 0);
