// The page in a real browser: builds the .wasm, serves the page on localhost, and drives
// Debian's Chromium headless through playwright-core. Fails (exit 1) unless:
// - the .wasm is at most 156 KB, the page loads with no console error and no request
//   beyond localhost, and its frames advance;
// - a click lets go of the penguin, which lands within 1 cm of the closed-form arc from its
//   release;
// - a swipe across the rope cuts it, and the two pieces are drawn as two curves;
// - a catapult frame (step + draw list) costs at most 1 ms in the browser;
// - the boat scene runs without slow motion;
// - the grappling hook reels in while the button is held, and a click on a hook in reach
//   throws the rope to it;
// - on a phone (412×915 CSS px, touch, held upright and then sideways): the page does not
//   scroll, the scene fills the screen, the help says "tap", the rope is drawn at least a
//   fifth of the screen's short side long, a tap lets go, the camera keeps the flying
//   penguin on screen, and a finger swipe cuts the rope.
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
check(size <= 156 * 1024, `dunas_web.wasm is ${(size / 1024).toFixed(1)} KB (at most 156 KB)`);

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
  await guard(page, origin, '', errors, outside);
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
  await page.screenshot({ path: path.join(out, 'catapult.png') });
  await page.waitForFunction(() => window.dunas.wasm.penguin() === 2, null, { timeout: 20000 });
  const { landed, arc, stretch } = await page.evaluate(() => ({
    landed: window.dunas.wasm.landed_x(),
    arc: window.dunas.wasm.arc_x(),
    stretch: window.dunas.wasm.largest_stretch(),
  }));
  check(Math.abs(landed - arc) <= 0.01,
    `the penguin landed at x = ${landed.toFixed(4)} m; the closed-form arc lands at ${arc.toFixed(4)} m (within 1 cm)`);
  check(stretch <= 0.005, `the rope's largest stretch under the penguin: ${(stretch * 100).toFixed(3)}% (at most 0.5%)`);
  await page.screenshot({ path: path.join(out, 'landed.png') });

  // A new game (a click once landed), then a swipe across the rope between particles 3 and 4.
  await page.mouse.click(box.x + box.width * 0.7, box.y + box.height * 0.3);
  await page.waitForFunction(() => window.dunas.wasm.penguin() === 0 && window.dunas.wasm.time() > 1.0);
  // Paused, so that the stroke meets the rope where it was seen however slow the browser.
  await page.evaluate(() => { window.dunas.paused = true; });
  const [from, to] = await swipeAcross(page, box, 200);
  await page.mouse.move(...from);
  await page.mouse.down();
  await page.mouse.move(...to, { steps: 4 });
  await page.mouse.up();
  await page.evaluate(() => { window.dunas.paused = false; });
  await page.waitForTimeout(600);
  const { pieces, drawn } = await page.evaluate(() => ({
    pieces: window.dunas.wasm.pieces(),
    drawn: window.dunas.drawnPieces(),
  }));
  check(pieces === 2 && drawn === 2, `the swipe cut the rope: ${pieces} pieces, drawn as ${drawn} curves`);
  await page.screenshot({ path: path.join(out, 'cut.png') });

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
  await page.screenshot({ path: path.join(out, 'boats.png') });

  // The grappling hook: holding the button away from the hooks reels in; a click on the
  // next hook once it is green (in reach) throws the rope there.
  await page.click('#grapple');
  await page.waitForFunction(() => window.dunas.scene() === 2 && window.dunas.wasm.time() > 0.5, null, { timeout: 20000 });
  const before = await page.evaluate(() => window.dunas.wasm.rope_length());
  await page.mouse.move(box.x + 10, box.y + box.height - 10);
  await page.mouse.down();
  await page.waitForTimeout(1000);
  await page.mouse.up();
  const reeled = await page.evaluate(() => window.dunas.wasm.rope_length());
  check(reeled < before - 1.5, `holding the button reeled the rope in from ${before.toFixed(2)} m to ${reeled.toFixed(2)} m`);
  let caught = false;
  for (let tries = 0; tries < 80 && !caught; tries++) {
    const [x, y] = await page.evaluate(() => window.dunas.hookOnPage(1));
    await page.mouse.click(x, y);
    caught = await page.evaluate(() => window.dunas.wasm.hook() === 1);
    if (!caught) await page.waitForTimeout(100);
  }
  await page.waitForTimeout(800);
  const grapple = await page.evaluate(() => ({
    hook: window.dunas.wasm.hook(),
    off: window.dunas.wasm.largest_off(),
    slow: window.dunas.wasm.slow_frames(),
  }));
  check(caught && grapple.hook === 1 && grapple.slow === 0 && grapple.off <= 0.005,
    `a click on the second hook threw the rope there (hook ${grapple.hook + 1}); the chain within ${(grapple.off * 100).toFixed(3)}% of the rope's length, ${grapple.slow} slow frames`);
  await page.screenshot({ path: path.join(out, 'grapple.png') });

  await phoneChecks(browser, origin, errors, outside);

  check(errors.length === 0, `no console errors${errors.length ? `: ${errors.join(' | ')}` : ''}`);
  check(outside.length === 0, `no request beyond localhost${outside.length ? `: ${outside.join(' ')}` : ''}`);
  console.log(`screenshots in ${out}`);
} finally {
  await browser.close();
  server.close();
}
/// Collects `page`'s console errors and uncaught exceptions into `errors` (each headed by
/// `tag`) and aborts, into `outside`, every request beyond `origin`.
async function guard(page, origin, tag, errors, outside) {
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`${tag}${m.text()}`); });
  page.on('pageerror', (e) => errors.push(`${tag}${e}`));
  await page.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith(origin)) return route.continue();
    outside.push(url);
    return route.abort();
  });
}

/// The page on a phone: 412×915 CSS px at 2.625 screen pixels each, touch only.
async function phoneChecks(browser, origin, errors, outside) {
  const phone = await browser.newContext({
    viewport: { width: 412, height: 915 }, deviceScaleFactor: 2.625, isMobile: true, hasTouch: true,
  });
  const page = await phone.newPage();
  await guard(page, origin, 'phone: ', errors, outside);
  await page.goto(`${origin}/`);
  await page.waitForFunction(() => window.dunas && window.dunas.wasm.time() > 1.0, null, { timeout: 20000 });
  // The screen as the page lays it out, and the rope's drawn length along its particles.
  const layout = () => page.evaluate(() => {
    const r = document.getElementById('view').getBoundingClientRect();
    let rope = 0;
    for (let i = 0; i < 7; i++) {
      const [a, b] = [window.dunas.particleOnPage(i), window.dunas.particleOnPage(i + 1)];
      rope += Math.hypot(b[0] - a[0], b[1] - a[1]);
    }
    const doc = document.documentElement;
    return {
      w: innerWidth, h: innerHeight, canvas: [r.width, r.height], rope,
      scrolls: doc.scrollHeight > innerHeight || doc.scrollWidth > innerWidth,
      help: document.getElementById('help').textContent,
    };
  });
  for (const [name, size] of [['upright', { width: 412, height: 915 }], ['sideways', { width: 915, height: 412 }]]) {
    await page.setViewportSize(size);
    await page.waitForTimeout(700);
    const l = await layout();
    const short = Math.min(l.w, l.h);
    check(!l.scrolls, `phone ${name} (${l.w}×${l.h}): the page does not scroll`);
    check(l.canvas[0] >= 0.99 * l.w && l.canvas[1] >= 0.8 * l.h,
      `phone ${name}: the scene fills the screen (${l.canvas.map((v) => v.toFixed(0)).join('×')} px)`);
    check(l.rope >= 0.2 * short,
      `phone ${name}: the rope is drawn ${l.rope.toFixed(0)} px long, ${(100 * l.rope / short).toFixed(0)}% of the screen's short side (at least 20%)`);
    await page.screenshot({ path: path.join(out, `phone-${name}.png`) });
  }
  const help = (await layout()).help;
  check(/\btap\b/i.test(help) && !/click/i.test(help), `the phone's help says tap: "${help}"`);

  // A tap lets go; the camera keeps the penguin on screen all the way down.
  await page.setViewportSize({ width: 412, height: 915 });
  await page.waitForTimeout(300);
  const box = await page.locator('#view').boundingBox();
  // Tapped as the penguin rises forward, so that it flies a while.
  await page.waitForFunction(() => {
    const v = window.dunas.wasm;
    const [x0, y0, x1, y1] = [v.particle(6, 0), v.particle(6, 1), v.particle(7, 0), v.particle(7, 1)];
    return y1 < y0 && x1 > x0 && v.particle(7, 1) < v.particle(0, 1);
  }, null, { timeout: 5000 });
  await page.touchscreen.tap(box.x + box.width * 0.5, box.y + box.height * 0.3);
  await page.waitForFunction(() => window.dunas.wasm.penguin() === 1, null, { timeout: 5000 });
  // Every frame the page draws until the penguin lands, looked at in the page itself.
  const looks = await page.evaluate(() => new Promise((resolve) => {
    const seen = [];
    const look = () => {
      if (window.dunas.wasm.penguin() !== 1) return resolve(seen);
      seen.push(window.dunas.penguinOnPage());
      requestAnimationFrame(look);
    };
    look();
  }));
  const seen = looks.length;
  const off = looks.filter((at) => !at || at[0] < box.x || at[0] > box.x + box.width
    || at[1] < box.y || at[1] > box.y + box.height).length;
  check(seen > 3 && off === 0, `a tap let go; the flying penguin stayed on screen (${seen - off} of ${seen} frames)`);
  await page.screenshot({ path: path.join(out, 'phone-landed.png') });

  // A tap once it landed starts a new game; a finger swipes across the rope between
  // particles 3 and 4 (touch events, as a finger sends them).
  await page.waitForFunction(() => window.dunas.wasm.penguin() === 2, null, { timeout: 20000 });
  await page.touchscreen.tap(box.x + box.width * 0.5, box.y + box.height * 0.3);
  await page.waitForFunction(() => window.dunas.wasm.penguin() === 0 && window.dunas.wasm.time() > 1.5, null, { timeout: 10000 });
  const cdp = await phone.newCDPSession(page);
  await page.evaluate(() => { window.dunas.paused = true; });
  const [from, to] = await swipeAcross(page, box, 120);
  const touch = (type, t) => cdp.send('Input.dispatchTouchEvent', {
    type, touchPoints: t === null ? [] : [{ x: from[0] + (to[0] - from[0]) * t, y: from[1] + (to[1] - from[1]) * t }],
  });
  await touch('touchStart', 0);
  for (let k = 1; k <= 4; k++) await touch('touchMove', k / 4);
  await touch('touchEnd', null);
  await page.evaluate(() => { window.dunas.paused = false; });
  await page.waitForTimeout(600);
  const pieces = await page.evaluate(() => window.dunas.wasm.pieces());
  check(pieces === 2, `a finger swipe cut the rope: ${pieces} pieces`);
  await page.screenshot({ path: path.join(out, 'phone-cut.png') });
  await phone.close();
}

/// A swipe across the rope between its particles 3 and 4 (the game paused), as `[from, to]`
/// page points: up to `most` px each side of it and within the canvas `box` (a touch starts
/// on the canvas).
async function swipeAcross(page, box, most) {
  const [a, b] = await page.evaluate(() => [window.dunas.particleOnPage(3), window.dunas.particleOnPage(4)]);
  const mid = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
  const along = Math.hypot(b[0] - a[0], b[1] - a[1]);
  const dir = [-(b[1] - a[1]) / along, (b[0] - a[0]) / along];
  let reach = most;
  for (const sign of [-1, 1]) {
    for (const k of [0, 1]) {
      const [lo, hi] = k === 0 ? [box.x + 4, box.x + box.width - 4] : [box.y + 4, box.y + box.height - 4];
      const d = sign * dir[k];
      if (d > 0) reach = Math.min(reach, (hi - mid[k]) / d);
      if (d < 0) reach = Math.min(reach, (lo - mid[k]) / d);
    }
  }
  return [[mid[0] - dir[0] * reach, mid[1] - dir[1] * reach], [mid[0] + dir[0] * reach, mid[1] + dir[1] * reach]];
}

if (failures.length) {
  console.error(`\nthe browser test failed: ${failures.length} check(s)`);
  process.exit(1);
}
console.log('\nthe browser test passed');
