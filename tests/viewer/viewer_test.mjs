// The viewer in a real browser: Debian's chromium, headless, driven by playwright-core
// (report/viewer-src/package.json; `npm ci` there, which ./run does). Run by ctest as
//   node viewer_test.mjs GRASPCD SOURCE_DIR WORK_DIR
// It records example 1 with `graspcd trajectory`, bundles the page with build.mjs, opens it from
// file:// and checks: no console or page errors, WebGL drew something, the same state renders the
// same frame twice, moving the step slider changes the frame, and toggling our contacts (and
// MuJoCo's native ones) changes it. Exit 77 (ctest's SKIP_RETURN_CODE) only when
// /usr/bin/chromium is absent.
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const CHROMIUM = '/usr/bin/chromium';
const [graspcd, source, work] = process.argv.slice(2).map((a) => resolve(a));
if (!work) {
  console.error('usage: node viewer_test.mjs GRASPCD SOURCE_DIR WORK_DIR');
  process.exit(2);
}
if (!existsSync(CHROMIUM)) {
  console.log(`SKIP: ${CHROMIUM} is absent (apt-get install chromium; ./run test installs it)`);
  process.exit(77);
}
const viewerSrc = join(source, 'report/viewer-src');
if (!existsSync(join(viewerSrc, 'node_modules/playwright-core'))) {
  console.error(`${viewerSrc}/node_modules: missing; run npm ci there (./run test does)`);
  process.exit(1);
}
const { chromium } = createRequire(join(viewerSrc, 'package.json'))('playwright-core');

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures += 1;
}

rmSync(work, { recursive: true, force: true });
mkdirSync(work, { recursive: true });
const trajectory = join(work, 'example1.json');
const page_path = join(work, 'viewer.html');
execFileSync(graspcd, ['trajectory', join(source, 'mjcf/example1.xml'), '--methods', 'sat,neurosat',
  '--out', trajectory], { stdio: 'inherit' });
execFileSync(process.execPath, [join(viewerSrc, 'build.mjs'), page_path, trajectory],
  { stdio: 'inherit' });

const browser = await chromium.launch({
  executablePath: CHROMIUM,
  headless: true,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1200, height: 700 } });
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => errors.push(`page error: ${e.message}`));
  await page.goto(pathToFileURL(page_path).href);
  await page.waitForSelector('body[data-ready="1"]', { timeout: 15000 });
  const view = page.locator('#view');
  const shot = () => view.screenshot();
  const steps = Number(await page.locator('#step').getAttribute('max')) + 1;
  check(steps > 10, `the page has the grasp's ${steps} steps`);

  // WebGL drew the scene: the canvas is not one colour.
  const colours = await page.evaluate(() => {
    const c = document.getElementById('view');
    const gl = c.getContext('webgl2') || c.getContext('webgl');
    const px = new Uint8Array(c.width * c.height * 4);
    gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
    const seen = new Set();
    for (let i = 0; i < px.length; i += 4 * 97) seen.add((px[i] << 16) | (px[i + 1] << 8) | px[i + 2]);
    return seen.size;
  });
  check(colours > 20, `WebGL drew the scene (${colours} colours sampled)`);

  const first = await shot();
  check(Buffer.compare(first, await shot()) === 0, 'the same state renders the same frame');
  await page.locator('#step').fill(String(steps - 1));
  const label = await page.locator('#stepLabel').textContent();
  check(label.startsWith(`${steps} / ${steps}`), `the slider moved to the last step ("${label}")`);
  const last = await shot();
  check(Buffer.compare(first, last) !== 0, 'moving the slider changes the rendered frame');

  check(/^\d+ \/ \d+: [1-9]\d* contacts/.test(label), 'the last step has contacts');
  await page.locator('#ours').uncheck();
  const noContacts = await shot();
  check(Buffer.compare(last, noContacts) !== 0, 'hiding our contacts changes the frame');
  await page.locator('#ours').check();
  check(Buffer.compare(last, await shot()) === 0, 'showing them again restores the frame');
  await page.locator('#native').check();
  check(Buffer.compare(last, await shot()) !== 0, "showing MuJoCo's native contacts changes it");
  await page.locator('.obb[data-level="1"]').check();
  check(Buffer.compare(last, await shot()) !== 0, 'showing OBB depth 1 changes it');

  const legend = await page.locator('#legend').textContent();
  check(legend.includes('sat:') && legend.includes('neurosat:'), `the time plot's legend: ${legend}`);
  check(errors.length === 0, `no console or page errors${errors.length ? ': ' + errors.join('; ') : ''}`);
} finally {
  await browser.close();
}
process.exit(failures === 0 ? 0 : 1);
