#!/bin/sh
# The worksheet of docs/teaching.md as PDFs, printed by Debian's Chromium from the HTML sources
# docs/worksheet.en.html and docs/worksheet.de.html (their print stylesheet: docs/worksheet.css).
#   scripts/make-worksheet.sh [--build DIR] [--out DIR] [--check-links] [--images]
# --out DIR      where the PDFs go (default: the build folder): worksheet-en.pdf, worksheet-de.pdf
# --check-links  open every page link of docs/teaching*.md and docs/worksheet*.html (the `#machine=…`
#                ones) in DIR/web/whatnext.html in headless Chromium (playwright-core from
#                DIR/web-npm, as the page tests use it) and check that the page names no problem with
#                the link and shows the outcome DIR/whatnext prints for the same machine
# --images       also write docs/img/teaching-*.png: the lesson's steps and the worksheet's first page
# --build DIR    the build folder (default: build)
set -eu
cd "$(dirname "$0")/.."
ROOT=$(pwd)
BUILD=build OUT='' CHECK=0 IMAGES=0
while [ $# -gt 0 ]; do
  case "$1" in
    --build) BUILD=$2; shift 2 ;;
    --out) OUT=$2; shift 2 ;;
    --check-links) CHECK=1; shift ;;
    --images) IMAGES=1; CHECK=1; shift ;;
    *) echo "make-worksheet: unknown option '$1' (--build DIR, --out DIR, --check-links, --images)" >&2; exit 2 ;;
  esac
done
OUT=${OUT:-$BUILD}
mkdir -p "$OUT"
CHROMIUM=${WHATNEXT_CHROMIUM:-/usr/bin/chromium}
# Root in a container, no GPU, no network of its own; a fresh profile every time.
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
FLAGS="--headless --no-sandbox --disable-gpu --disable-background-networking --no-first-run --user-data-dir=$TMP/profile"

for lang in en de; do
  # shellcheck disable=SC2086
  "$CHROMIUM" $FLAGS --no-pdf-header-footer --print-to-pdf="$OUT/worksheet-$lang.pdf" \
    "file://$ROOT/docs/worksheet.$lang.html" 2>/dev/null
  [ -s "$OUT/worksheet-$lang.pdf" ] || { echo "make-worksheet: Chromium wrote no $OUT/worksheet-$lang.pdf" >&2; exit 1; }
  echo "$OUT/worksheet-$lang.pdf"
done

[ "$CHECK" = 1 ] || exit 0
GIVEN=$BUILD
BUILD=$(cd "$GIVEN" 2>/dev/null && pwd) || { echo "make-worksheet: no build folder '$GIVEN'" >&2; exit 2; }
[ -f "$BUILD/web/whatnext.html" ] || { echo "make-worksheet: no page at $BUILD/web/whatnext.html (build with WHATNEXT_WEB=ON)" >&2; exit 2; }
[ -x "$BUILD/whatnext" ] || { echo "make-worksheet: no $BUILD/whatnext" >&2; exit 2; }
IMGDIR=
[ "$IMAGES" = 1 ] && IMGDIR=$ROOT/docs/img
ROOT="$ROOT" BUILD="$BUILD" CHROMIUM="$CHROMIUM" IMGDIR="$IMGDIR" node - <<'EOF'
'use strict';
const fs = require('fs');
const path = require('path');
const { spawnSync } = require('child_process');
const { ROOT, BUILD, CHROMIUM, IMGDIR } = process.env;
const { chromium } = require(require.resolve('playwright-core', { paths: [path.join(BUILD, 'web-npm/node_modules')] }));

// Every link of the teaching pages: a `#machine=…` in a code span (Markdown) or an element (HTML).
const docs = fs.readdirSync(path.join(ROOT, 'docs')).filter((f) => /^(teaching.*\.md|worksheet.*\.html)$/.test(f));
const links = new Set();
for (const f of docs) {
  const text = fs.readFileSync(path.join(ROOT, 'docs', f), 'utf8').replace(/&amp;/g, '&');
  for (const m of text.matchAll(/[`>](#machine=[^`<\s]*)[`<]/g)) links.add(m[1]);
}
// The lesson's steps as pictures: the link, the event to show, the picture's name.
const steps = [['#machine=example1', 'rope_taut', 'teaching-jerk'],
               ['#machine=example1&compare=laws:', 'balloon_caught', 'teaching-laws'],
               ['#machine=example1&rope.stiffness=100000&compare=rigid:', 'rope_slack', 'teaching-stretchy'],
               ['#machine=konstanz', 'lid_open', 'teaching-konstanz']];

// What the command line says of the link's machine: --example and --set as the page applies them.
function cliOutcome(hash) {
  const p = new URLSearchParams(hash.slice(1));
  const id = p.get('machine');
  const args = ['run', '-q', ...(id === 'radio' ? [path.join(ROOT, 'examples/example1-radio.toml')] : ['--example', id.replace(/^example/, '')])];
  for (const [k, v] of p) if (k.includes('.')) args.push('--set', `${k}=${v}`);
  const r = spawnSync(path.join(BUILD, 'whatnext'), args, { encoding: 'utf8' });
  return r.status === 0 ? `Outcome: ${r.stdout.trim()}.` : `the command line refuses it: ${r.stderr.trim()}`;
}

(async () => {
  const browser = await chromium.launch({ executablePath: CHROMIUM, headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking'] });
  const page = await browser.newPage({ viewport: { width: 1366, height: 768 }, locale: 'en-GB' });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  let failed = 0;
  const open = async (hash) => {
    await page.goto('about:blank');
    await page.goto(`file://${BUILD}/web/whatnext.html${hash}`);
    await page.waitForSelector('body[data-ready]', { timeout: 60000 });
    await page.waitForFunction(() => document.body.dataset.busy === 'false', null, { timeout: 60000 });
    return page.evaluate(() => {
      const text = (id) => { const e = document.getElementById(id); return e && !e.hidden ? e.textContent.trim() : ''; };
      const box = document.getElementById('compare-outcome');
      const lines = box.hidden ? [] : box.children.length ? [...box.children].map((e) => e.textContent.trim()) : [box.textContent.trim()];
      return { outcome: text('outcome'), compare: lines.join(' | '), lines, problem: text('problem') };
    });
  };
  for (const hash of [...links].sort()) {
    const shown = await open(hash);
    const bad = [];
    if (shown.problem) bad.push(`the page says: ${shown.problem}`);
    const expected = cliOutcome(hash);
    if (!/[&#]lang=/.test(hash) && shown.outcome !== expected) bad.push(`the page shows "${shown.outcome}", the command line "${expected}"`);
    // A comparison shows its run's outcome ("Dashed, …: …"), or all four laws' outcomes.
    const compared = /compare=laws:/.test(hash)
      ? shown.lines.length === 4 && shown.lines.every((l) => /^(rope|angular-momentum-sum|kinetic-energy|linear-momentum): /.test(l))
      : shown.lines.length === 1 && /^(Dashed|Gestrichelt), /.test(shown.lines[0]);
    if (/compare=/.test(hash) && !compared) bad.push(`no comparison: "${shown.compare}"`);
    // Each law's outcome as the command line gives it with that law.
    if (compared && /compare=laws:/.test(hash) && !/[&#]lang=/.test(hash)) {
      for (const line of shown.lines) {
        const law = line.split(':')[0];
        const cli = cliOutcome(`${hash}&run.impact_law=${law}`).replace(/^Outcome: (.*)\.$/, '$1');
        if (line !== `${law}: ${cli}`) bad.push(`the page shows "${line}", the command line "${law}: ${cli}"`);
      }
    }
    if (errors.length) bad.push(...errors.splice(0));
    failed += bad.length ? 1 : 0;
    console.log(`${bad.length ? 'FAIL' : 'ok  '} ${hash}  ${shown.outcome} ${shown.compare}`.trim());
    for (const b of bad) console.log(`       ${b}`);
  }
  if (IMGDIR) {
    for (const [hash, event, name] of steps) {
      await open(hash);
      await page.click(`#timeline tr:has-text("${event}")`);
      await page.waitForTimeout(300);
      await page.screenshot({ path: path.join(IMGDIR, `${name}.png`) });
      console.log(path.join('docs/img', `${name}.png`));
    }
    // The worksheet's first page as the printed A4 shows it (210 mm at 96 px/in is 794 px), with
    // the @page margins of docs/worksheet.css (12 mm, 14 mm) as padding: up to the page break.
    await page.setViewportSize({ width: 794, height: 1123 });
    await page.goto(`file://${ROOT}/docs/worksheet.en.html`);
    await page.emulateMedia({ media: 'print' });
    await page.addStyleTag({ content: 'body { padding: 12mm 14mm !important; }' });
    const end = await page.evaluate(() => document.querySelector('.page-break').getBoundingClientRect().top);
    await page.screenshot({ path: path.join(IMGDIR, 'teaching-worksheet.png'), clip: { x: 0, y: 0, width: 794, height: Math.min(1123, Math.ceil(end)) } });
    console.log('docs/img/teaching-worksheet.png');
  }
  await browser.close();
  if (failed) { console.error(`make-worksheet: ${failed} of ${links.size} links failed`); process.exit(1); }
  console.log(`make-worksheet: all ${links.size} links of ${docs.join(', ')} open as the command line runs them`);
})().catch((e) => { console.error(`make-worksheet: ${e.message}`); process.exit(1); });
EOF
