// Builds the page's .wasm and serves the page on localhost (no network needed, node only).
//
//   node web/serve.mjs            build, then serve on http://localhost:8000
//   PORT=9000 node web/serve.mjs  another port
//
// web/test.mjs imports `build` and `serve`.
import { spawnSync } from 'node:child_process';
import { createServer } from 'node:http';
import { readFile } from 'node:fs/promises';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const here = path.dirname(fileURLToPath(import.meta.url));
const repo = path.dirname(here);
/** Cargo's target directory ($CARGO_TARGET_DIR, or target/). */
export const targetDir = process.env.CARGO_TARGET_DIR
  ? path.resolve(repo, process.env.CARGO_TARGET_DIR)
  : path.join(repo, 'target');
/** Where cargo writes the page's module. */
export const wasmPath = path.join(targetDir, 'wasm32-unknown-unknown', 'web', 'dunas_web.wasm');

/** `cargo build --profile web -p dunas-web --target wasm32-unknown-unknown`; throws if it fails. */
export function build() {
  const args = ['build', '--profile', 'web', '-p', 'dunas-web', '--target', 'wasm32-unknown-unknown'];
  const run = spawnSync('cargo', args, { cwd: repo, stdio: 'inherit' });
  if (run.status !== 0) throw new Error(`cargo ${args.join(' ')} failed`);
}

const files = {
  '/': [path.join(here, 'index.html'), 'text/html; charset=utf-8'],
  '/index.html': [path.join(here, 'index.html'), 'text/html; charset=utf-8'],
  '/main.js': [path.join(here, 'main.js'), 'text/javascript; charset=utf-8'],
  '/dunas_web.wasm': [wasmPath, 'application/wasm'],
};

/** Serves the page on `port` (0 picks a free one); resolves to the server once listening. */
export function serve(port) {
  const server = createServer(async (req, res) => {
    const file = files[new URL(req.url, 'http://localhost').pathname];
    if (!file) {
      res.writeHead(404).end('not found');
      return;
    }
    try {
      const body = await readFile(file[0]);
      res.writeHead(200, { 'content-type': file[1], 'cache-control': 'no-store' }).end(body);
    } catch (e) {
      res.writeHead(500).end(String(e));
    }
  });
  return new Promise((resolve) => server.listen(port, '127.0.0.1', () => resolve(server)));
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  build();
  const server = await serve(Number(process.env.PORT ?? 8000));
  console.log(`dunas page on http://localhost:${server.address().port}/ (Ctrl-C stops)`);
}
