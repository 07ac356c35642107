// Every device example in WebAssembly, played in headless Chromium: the wasm32 rows of
// docs/devices.md (`.ci/devices` builds the modules and calls this).
//
//   node web/devices.mjs mcu_rope mcu_peg ...
//
// Each example's `.wasm` (`cargo build --release --target wasm32-unknown-unknown --example
// NAME`; `examples/common/device.rs`, module `browser`) plays its 600 frames in Q16.16 and in
// f32 in a page made cross-origin isolated, where `performance.now()` steps by 5 µs (100 µs
// otherwise); `mcu_golden`, the rollback scene, is played a frame a call from `web/golden/`'s
// `.wasm` instead. After a run that warms the engine up, TIMED runs time every frame (its
// step and its drawing, through the clock the page gives the example) and WHOLE runs time
// only the whole run, in turn. A frame's time is the mean of its TIMED runs but those more
// than a step of the clock over the frame's median (a stall of the machine): the clock's
// steps average out to about a microsecond. The worst frame is the largest of these; the
// mean frame is a whole run's time over 600, of the fastest and of the median run (the
// clock is not read inside those runs). Every run's checksum must agree.
//
// Prints `chromium VERSION`, then a line a run, tab-separated: example, format, checksum,
// worst (ns), mean of the fastest and of the median run (ns), the `.wasm`'s size and the
// stack's high-water mark (bytes; Rust's wasm32 keeps the stack in the first 1 MiB of
// memory, which the first run paints).
// Exits 1 when a run fails.
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { targetDir } from './serve.mjs';

/** Runs timed frame by frame, and runs timed as a whole. */
const TIMED = 25;
const WHOLE = 9;
/** The clock's step in an isolated page (ms). */
const RESOLUTION = 0.005;
const FRAMES = 600;
const examples = process.argv.slice(2);
const modules = path.join(targetDir, 'wasm32-unknown-unknown', 'release');
const file = (name) => (name === 'mcu_golden'
  ? path.join(modules, 'dunas_golden.wasm')
  : path.join(modules, 'examples', `${name}.wasm`));

/** In the page: `timed` runs of example `name` in `format` timed frame by frame (`times`,
 * ms) and `whole` runs timed as a whole only (`total`, ms; the example's clock then reads
 * 0), taken in turn after one run to warm the engine up, each with its checksum, and the
 * stack's high-water mark in that first run (bytes): `{ runs, stack }`, or `{ error }` when
 * one fails. */
async function play({ name, format, timed: frameByFrame, whole, frames }) {
  const module = await WebAssembly.compileStreaming(fetch(`/${name}.wasm`));
  const golden = name === 'mcu_golden';
  const [STACK_TOP, PAINT] = [1 << 20, 0xa5];
  const runs = [];
  let stack = 0;
  for (let round = 0, left = [frameByFrame, whole]; left[0] + left[1] > 0; round++) {
    // Frame by frame while more such runs are left than whole ones, and once to warm up.
    const timed = round === 0 || left[0] >= left[1];
    const times = [];
    const clock = timed ? () => performance.now() : () => 0;
    const meter = { now: clock, frame: (ms) => times.push(ms) };
    const e = (await WebAssembly.instantiate(module, golden ? {} : { meter })).exports;
    // The warm-up run measures the stack: Rust's wasm32 puts it first in memory, below
    // its 1 MiB top (where the data begins), so that region is painted and the lowest
    // byte the run changed is its high-water mark.
    const memory = new Uint8Array(e.memory.buffer);
    if (round === 0) {
      if (!(e.__data_end.value > STACK_TOP && memory.subarray(0, STACK_TOP).every((b) => b === 0))) {
        return { error: 'the stack is not the first 1 MiB of memory' };
      }
      memory.fill(PAINT, 0, STACK_TOP);
    }
    let checksum = -1;
    const start = performance.now();
    if (golden) {
      if (!e.begin(format)) return { error: 'the rollback scene did not start' };
      for (let k = 0; k < frames; k++) {
        const t0 = clock();
        if (!e.advance()) return { error: `the rollback scene refused frame ${k + 1}` };
        times.push(clock() - t0);
      }
    } else {
      checksum = Number(e.run(format));
    }
    const total = performance.now() - start;
    if (golden) {
      // The example's checksum: the folded state checksums, their halves xored.
      const h = BigInt.asUintN(64, format === 0 ? e.golden_q16() : e.golden_f32());
      checksum = Number((h ^ (h >> 32n)) & 0xffffffffn);
    }
    if (checksum < 0) return { error: 'the simulation failed' };
    if (times.length !== frames) return { error: `${times.length} frames played, not ${frames}` };
    if (round === 0) {
      const painted = new Uint8Array(e.memory.buffer, 0, STACK_TOP);
      stack = STACK_TOP - painted.findIndex((b) => b !== PAINT);
    } else {
      runs.push(timed ? { checksum, times } : { checksum, total });
      left[timed ? 0 : 1] -= 1;
    }
  }
  return { runs, stack };
}

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--no-first-run'],
});
let failed = false;
try {
  const page = await browser.newPage();
  // localhost (a secure context, which isolation needs) answered from here, no server: the
  // page with the headers that isolate it, and the modules from the same origin.
  const origin = 'http://localhost:9';
  await page.route(`${origin}/**`, (route) => {
    const url = new URL(route.request().url());
    const isolated = {
      'cross-origin-opener-policy': 'same-origin',
      'cross-origin-embedder-policy': 'require-corp',
    };
    if (url.pathname === '/') {
      return route.fulfill({ status: 200, contentType: 'text/html', headers: isolated, body: '<!doctype html><title>devices</title>' });
    }
    const name = url.pathname.match(/^\/([a-z_]+)\.wasm$/)?.[1];
    if (!name || !examples.includes(name)) return route.fulfill({ status: 404, body: 'not found' });
    return route.fulfill({ status: 200, contentType: 'application/wasm', headers: isolated, body: readFileSync(file(name)) });
  });
  await page.goto(`${origin}/`);
  if (!(await page.evaluate(() => crossOriginIsolated))) throw new Error('the page is not cross-origin isolated');
  console.log(`chromium ${browser.version()}`);

  for (const name of examples) {
    const bytes = readFileSync(file(name)).length;
    for (const [format, label] of [[0, 'q16'], [1, 'f32']]) {
      const played = await page.evaluate(play, { name, format, timed: TIMED, whole: WHOLE, frames: FRAMES });
      if (played.error) {
        console.error(`${name} (${label}): ${played.error}`);
        failed = true;
        continue;
      }
      const { runs, stack } = played;
      const sums = new Set(runs.map((r) => r.checksum));
      if (sums.size !== 1) {
        console.error(`${name} (${label}): the runs disagree: ${[...sums]}`);
        failed = true;
        continue;
      }
      const timed = runs.filter((r) => r.times);
      const median = (xs) => xs.sort((a, b) => a - b)[xs.length >> 1];
      // A frame's time: the mean of its runs but those a step of the clock over its median.
      const frame = (k) => {
        const times = timed.map((r) => r.times[k]);
        const kept = times.filter((t) => t <= median([...times]) + RESOLUTION * 1.01);
        return kept.reduce((a, b) => a + b, 0) / kept.length;
      };
      const worst = Math.max(...Array.from({ length: FRAMES }, (_, k) => frame(k)));
      const means = runs.filter((r) => !r.times).map((r) => r.total / FRAMES).sort((a, b) => a - b);
      const ns = (ms) => (ms * 1e6).toFixed(0);
      const sum = [...sums][0].toString(16).padStart(8, '0');
      console.log([name, label, sum, ns(worst), ns(means[0]), ns(median(means)), bytes, stack].join('\t'));
    }
  }
} finally {
  await browser.close();
}
process.exit(failed ? 1 : 0);
