// Opens a report of `ccal report` in headless Chromium with every network request refused, and fails
// (exit 1, one line per problem) on a console error, an uncaught page error, a failed or non-local request, a
// chart that was not drawn, or a chart with fewer drawn marks (bars with an area) than expected. Saves a PNG
// of the whole page. Then prints it as the PDF of `ccal report --pdf` would be printed (print media, the width of
// an A4 page less its margins) and fails on anything wider than the paper, and shows it on screen in a window
// 1200 px wide (CCAL_SCREEN_WIDTH) and fails on anything wider than the window.
//   node web/check_report.mjs REPORT.html SCREENSHOT.png [CHROMIUM]
// Exit 77 (the test is skipped) when no Chromium is installed.
import { chromium } from 'playwright-core';
import { existsSync } from 'node:fs';
import { pathToFileURL } from 'node:url';

const [report, screenshot, browserPath = '/usr/bin/chromium'] = process.argv.slice(2);
if (!report || !screenshot) {
  console.error('usage: node check_report.mjs REPORT.html SCREENSHOT.png [CHROMIUM]');
  process.exit(2);
}
if (!existsSync(browserPath)) {
  console.log(`skipped: no Chromium at ${browserPath} (Debian package chromium; scripts/setup.sh installs it)`);
  process.exit(77);
}

// The outermost elements whose right edge passes `width` px (run in the page): each named by its section's id,
// its tag and class, and where it ends.
function outermostWider(width) {
  return [...document.querySelectorAll('body *')]
    .filter((e) => e.getBoundingClientRect().right > width + 1 && e.getClientRects().length)
    .filter((e) => !e.parentElement || e.parentElement.getBoundingClientRect().right <= width + 1)
    .map((e) => `${e.closest('[id]') ? e.closest('[id]').id + ' ' : ''}${e.tagName.toLowerCase()}${e.id ? '#' + e.id : ''}${e.className && typeof e.className === 'string'
      ? '.' + e.className.split(' ')[0] : ''} (${Math.round(e.getBoundingClientRect().right)} px)`);
}

const problems = [];
const browser = await chromium.launch({
  executablePath: browserPath,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
         '--disable-component-update', '--disable-sync'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1480, height: 900 } });
  const url = pathToFileURL(report).href;
  // The page must need nothing but itself: every other request is refused and counted.
  await page.route('**/*', (route) => {
    if (route.request().url() === url) return route.continue();
    problems.push(`request refused: ${route.request().url()}`);
    return route.abort();
  });
  page.on('console', (m) => { if (m.type() === 'error') problems.push(`console error: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('requestfailed', (r) => { if (r.url() !== url) problems.push(`failed request: ${r.url()}`); });
  await page.goto(url, { waitUntil: 'load' });
  // A page with charts (the report) draws them; a page without (the certificate) has nothing to wait for.
  if (await page.evaluate(() => document.querySelector('div.chart') !== null)) {
    await page.waitForFunction(() => window.ccalReport !== undefined, null, { timeout: 20000 });
    await page.evaluate(() => window.ccalReport);
  }
  // Drawn marks per chart: the children of Vega's mark groups (bars, line and rule paths, points), not the
  // axes or legends.
  const charts = await page.evaluate(() => [...document.querySelectorAll('div.chart')].map((d) => ({
    id: d.id,
    rendered: d.dataset.rendered === 'yes',
    marks: d.querySelectorAll('svg g.role-mark > *').length,
    // a bar counts when it has an area on the page (a bar from 0 on a log axis is drawn with none)
    bars: [...d.querySelectorAll('svg g.mark-rect.role-mark > path')].filter((b) => {
      const box = b.getBBox();
      return box.width > 0.5 && box.height > 0.5;
    }).length,
    lines: d.querySelectorAll('svg g.mark-line.role-mark > path').length,
    rules: d.querySelectorAll('svg g.mark-rule.role-mark > line').length,
  })));
  const minimum = (id) => (id.startsWith('pareto-') ? { bars: 2, lines: 1 }
    : id.startsWith('mc-') ? { bars: 10, lines: 1, rules: 4 }
    : id === 'paper-vs-exact' ? { bars: 6 }
    : id === 'sensed-input' ? { lines: 3 }
    // the allocation: a bar per source (the bundled example has 52) and the rules at 1 and at the largest λ
    : id === 'allocate-scale' ? { bars: Number(process.env.CCAL_EXPECTED_SOURCES || 2), rules: 2 }
    // the design: two bars (full budget, tolerances alone) per coefficient and the rule at 1
    : id === 'design-ratio' ? { bars: 2 * Number(process.env.CCAL_EXPECTED_COEFFICIENTS || 1), rules: 1 }
    // the statement: per coefficient its Type A and Type B shares of u_c² stacked; the noise-free example's
    // Type A share (1e-20 %) has no area, so at least one bar per coefficient
    : id === 'statement-split' ? { bars: Number(process.env.CCAL_EXPECTED_COEFFICIENTS || 1) }
    : {});
  for (const c of charts) {
    if (!c.rendered) problems.push(`chart ${c.id}: not drawn`);
    for (const [kind, least] of Object.entries(minimum(c.id)))
      if (c[kind] < least) problems.push(`chart ${c.id}: ${c[kind]} ${kind} drawn, expected at least ${least}`);
    console.log(`chart ${c.id}: ${c.marks} marks (${c.bars} bars, ${c.lines} lines, ${c.rules} rules)`);
  }
  const expected = Number(process.env.CCAL_EXPECTED_CHARTS || 0);
  if (expected && charts.length !== expected) problems.push(`${charts.length} charts, expected ${expected}`);
  await page.screenshot({ path: screenshot, fullPage: true });
  console.log(`screenshot: ${screenshot}`);
  // On screen, a window 1200 px wide (a laptop's browser) shows every table without a horizontal scroll bar.
  const screenWidth = Number(process.env.CCAL_SCREEN_WIDTH || 1200);
  await page.setViewportSize({ width: screenWidth, height: 900 });
  for (const w of (await page.evaluate(outermostWider, screenWidth)).slice(0, 10))
    problems.push(`in a window ${screenWidth} px wide, wider than the window: ${w}`);
  // A4's 210 mm less the side margins of the page's own @page rule (the report's 12 mm, the certificate's 14 mm),
  // at 96 CSS px per inch.
  const margins = await page.evaluate(() => {
    const toMm = (v) => (v.endsWith('mm') ? parseFloat(v) : NaN);
    for (const sheet of document.styleSheets)
      for (const rule of sheet.cssRules)
        if (rule instanceof CSSPageRule) return [toMm(rule.style.marginLeft), toMm(rule.style.marginRight)];
    return [NaN, NaN];
  });
  if (!margins.every(Number.isFinite)) problems.push(`no @page rule with side margins in mm: ${margins}`);
  const paper = Math.floor(((210 - margins[0] - margins[1]) / 25.4) * 96);
  await page.emulateMedia({ media: 'print' });
  await page.setViewportSize({ width: paper, height: 1000 });
  const wide = await page.evaluate(outermostWider, paper);
  for (const w of wide.slice(0, 10)) problems.push(`printed on A4 (${paper} px wide), wider than the paper: ${w}`);
} finally {
  await browser.close();
}
for (const p of problems) console.error(p);
process.exit(problems.length ? 1 : 0);
