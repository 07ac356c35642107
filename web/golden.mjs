// Rollback netplay's determinism in WebAssembly: runs the scripted scene of
// examples/common/golden.rs from the .wasm `cargo build --release -p dunas-golden --target
// wasm32-unknown-unknown` makes, in Q16.16 and in f32, and checks its
// folded state checksums against tests/golden.txt (which the host's tests and the
// microcontrollers reproduce). Node only; exits 1 on a difference.
// With `--costs`, it instead times every frame of the scene in V8 (Chromium's engine), nine
// rounds of its 600 frames in each format, and prints the rows of docs/devices.md's wasm32
// table: the worst frame and the mean of the quietest round (the least worst frame), in ns
// (`.ci/devices` calls it).
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.join(path.dirname(fileURLToPath(import.meta.url)), '..');
const target = process.env.CARGO_TARGET_DIR || path.join(root, 'target');
const wasm = path.join(target, 'wasm32-unknown-unknown', 'release', 'dunas_golden.wasm');
const { instance } = await WebAssembly.instantiate(readFileSync(wasm), {});
const golden = Object.fromEntries(
  readFileSync(path.join(root, 'tests', 'golden.txt'), 'utf8')
    .split('\n')
    .filter((line) => /^[a-z0-9]+=/.test(line))
    .map((line) => line.split('=')),
);
if (process.argv.includes('--costs')) {
  const size = (readFileSync(wasm).length / 1024).toFixed(1);
  for (const [format, name] of [[0, 'Q16.16'], [1, 'f32']]) {
    // Each round's worst frame and mean; the machine may stall any one frame, so the
    // table takes the quietest round (the least worst frame).
    const rounds = [];
    for (let round = 0; round < 9; round++) {
      instance.exports.begin(format);
      let [worst, sum] = [0, 0];
      for (let k = 0; k < 600; k++) {
        const t0 = performance.now();
        if (!instance.exports.advance()) throw new Error('the scene refused a step');
        const t = performance.now() - t0;
        [worst, sum] = [Math.max(worst, t), sum + t];
      }
      rounds.push([worst, sum / 600]);
    }
    const [worst, mean] = rounds.reduce((a, b) => (b[0] < a[0] ? b : a));
    console.log(`| wasm32 in V8 (node ${process.version}), ${name} | \`mcu_golden\` (the rollback scene) | ${(worst * 1e6).toFixed(0)} | ${(mean * 1e6).toFixed(0)} | ${size} KB |`);
  }
  process.exit(0);
}

let failed = false;
for (const format of ['q16', 'f32']) {
  const got = BigInt.asUintN(64, instance.exports[`golden_${format}`]()).toString(16).padStart(16, '0');
  const ok = got === golden[format].trim();
  failed ||= !ok;
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${format}: the .wasm's golden=${got}, tests/golden.txt's ${golden[format].trim()}`);
}
process.exit(failed ? 1 : 0);
