// The page in a real browser: builds the .wasm, serves the page on localhost, and drives
// Debian's Chromium headless through playwright-core. Fails (exit 1) unless:
// - the .wasm is at most 128 KB, the page loads with no console error and no request
//   beyond localhost, and its frames advance;
// - a click lets go of the penguin, which lands within 1 cm of the closed-form arc from its
//   release;
// - a swipe across the rope cuts it, and the two pieces are drawn as two curves;
// - a catapult frame (step + draw list) costs at most 1 ms in the browser;
// - the boat scene runs without slow motion.
// Screenshots go to target/web/. Run: `npm --prefix web test` (after `npm --prefix web ci`).
import { statSync, mkdirSync } from 'node:fs';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { build, serve, targetDir, wasmPath } from './serve.mjs';

const out = path.join(targetDir, 'web');
mkdirSync(out, { recursive: true });
const failures = [];
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures.push(what);
}

build();
const size = statSync(wasmPath).size;
check(size <= 128 * 1024, `dunas_web.wasm is ${(size / 1024).toFixed(1)} KB (at most 128 KB)`);

const server = await serve(0);
const origin = `http://127.0.0.1:${server.address().port}`;
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--no-first-run'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1000, height: 720 } });
  const errors = [];
  const outside = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith(origin)) return route.continue();
    outside.push(url);
    return route.abort();
  });
  await page.goto(`${origin}/`);
  await page.waitForFunction(() => window.dunas && window.dunas.wasm.time() > 0.5, null, { timeout: 20000 });

  const t0 = await page.evaluate(() => window.dunas.wasm.time());
  await page.waitForTimeout(500);
  const t1 = await page.evaluate(() => window.dunas.wasm.time());
  check(t1 > t0 + 0.2, `frames advance: ${t0.toFixed(2)} s, then ${t1.toFixed(2)} s half a second later`);

  // Let go after two seconds of whirling, with a click on the canvas.
  await page.waitForFunction(() => window.dunas.wasm.time() > 2.0);
  const box = await page.locator('#view').boundingBox();
  await page.mouse.click(box.x + box.width * 0.7, box.y + box.height * 0.3);
  await page.waitForFunction(() => window.dunas.wasm.penguin() === 1, null, { timeout: 5000 });
  await page.waitForTimeout(400);
  await page.locator('main').screenshot({ path: path.join(out, 'catapult.png') });
  await page.waitForFunction(() => window.dunas.wasm.penguin() === 2, null, { timeout: 20000 });
  const { landed, arc, stretch } = await page.evaluate(() => ({
    landed: window.dunas.wasm.landed_x(),
    arc: window.dunas.wasm.arc_x(),
    stretch: window.dunas.wasm.largest_stretch(),
  }));
  check(Math.abs(landed - arc) <= 0.01,
    `the penguin landed at x = ${landed.toFixed(4)} m; the closed-form arc lands at ${arc.toFixed(4)} m (within 1 cm)`);
  check(stretch <= 0.005, `the rope's largest stretch under the penguin: ${(stretch * 100).toFixed(3)}% (at most 0.5%)`);
  await page.locator('main').screenshot({ path: path.join(out, 'landed.png') });

  // A new game (a click once landed), then a swipe across the rope between particles 3 and 4.
  await page.mouse.click(box.x + box.width * 0.7, box.y + box.height * 0.3);
  await page.waitForFunction(() => window.dunas.wasm.penguin() === 0 && window.dunas.wasm.time() > 1.0);
  const [a, b] = await page.evaluate(() => [window.dunas.particleOnPage(3), window.dunas.particleOnPage(4)]);
  const mid = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
  const along = Math.hypot(b[0] - a[0], b[1] - a[1]);
  const across = [-(b[1] - a[1]) / along * 80, (b[0] - a[0]) / along * 80];
  await page.mouse.move(mid[0] - across[0], mid[1] - across[1]);
  await page.mouse.down();
  await page.mouse.move(mid[0] + across[0], mid[1] + across[1], { steps: 12 });
  await page.mouse.up();
  await page.waitForTimeout(600);
  const { pieces, drawn } = await page.evaluate(() => ({
    pieces: window.dunas.wasm.pieces(),
    drawn: window.dunas.drawnPieces(),
  }));
  check(pieces === 2 && drawn === 2, `the swipe cut the rope: ${pieces} pieces, drawn as ${drawn} curves`);
  await page.locator('main').screenshot({ path: path.join(out, 'cut.png') });

  // The catapult's frame cost in this browser: 5 rounds of 600 frames of a fresh game.
  const rounds = [];
  for (let r = 0; r < 5; r++) rounds.push(await page.evaluate(() => window.dunas.bench(600)));
  rounds.sort((x, y) => x - y);
  const median = rounds[2];
  check(median <= 1.0,
    `a catapult frame (step + draw list) costs ${median.toFixed(4)} ms median, ${rounds[0].toFixed(4)} ms fastest of 5 rounds of 600 (at most 1 ms)`);

  // The boats.
  await page.click('#boats');
  await page.waitForFunction(() => window.dunas.scene() === 1 && window.dunas.wasm.time() > 2.0, null, { timeout: 20000 });
  await page.mouse.click(box.x + box.width * 0.5, box.y + box.height * 0.5);
  await page.waitForTimeout(1500);
  const boats = await page.evaluate(() => ({
    slow: window.dunas.wasm.slow_frames(),
    time: window.dunas.wasm.time(),
    cost: window.dunas.frameCost(),
  }));
  check(boats.slow === 0 && boats.time > 3.0,
    `the boats sailed ${boats.time.toFixed(1)} s with ${boats.slow} slow frames; a frame of 9 sails costs ${boats.cost.toFixed(3)} ms`);
  await page.locator('main').screenshot({ path: path.join(out, 'boats.png') });

  check(errors.length === 0, `no console errors${errors.length ? `: ${errors.join(' | ')}` : ''}`);
  check(outside.length === 0, `no request beyond localhost${outside.length ? `: ${outside.join(' ')}` : ''}`);
  console.log(`screenshots in ${out}`);
} finally {
  await browser.close();
  server.close();
}
if (failures.length) {
  console.error(`\nthe browser test failed: ${failures.length} check(s)`);
  process.exit(1);
}
console.log('\nthe browser test passed');
