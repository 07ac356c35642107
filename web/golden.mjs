// Rollback netplay's determinism in WebAssembly: runs the scripted scene of
// examples/common/golden.rs from the .wasm `cargo build --release -p dunas-golden --target
// wasm32-unknown-unknown` makes, in Q16.16 and in f32, and checks its
// folded state checksums against tests/golden.txt (which the host's tests and the
// microcontrollers reproduce). Node only; exits 1 on a difference.
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
let failed = false;
for (const format of ['q16', 'f32']) {
  const got = BigInt.asUintN(64, instance.exports[`golden_${format}`]()).toString(16).padStart(16, '0');
  const ok = got === golden[format].trim();
  failed ||= !ok;
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${format}: the .wasm's golden=${got}, tests/golden.txt's ${golden[format].trim()}`);
}
process.exit(failed ? 1 : 0);
