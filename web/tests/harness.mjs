// Shared pieces of the browser tests and the benchmark: paths, a static file server for
// web/dist on 127.0.0.1, bounded waits, and Debian's headless Chromium through playwright-core
// (WebGL2 via ANGLE + SwiftShader; no GPU, display or browser download needed).
import { createServer } from 'node:http';
import { mkdtempSync, readFileSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

export const root = resolve(fileURLToPath(new URL('../..', import.meta.url)));
export const dist = resolve(process.env.PENUMBRA_WEB_DIST || join(root, 'web/dist'));
export const outDir = resolve(process.env.PENUMBRA_TEST_OUTPUT ||
                              join(root, 'build-web/test-output'));
export const chromiumPath = process.env.PENUMBRA_CHROMIUM || '/usr/lib/chromium/chromium';

export const CHROMIUM_ARGS = [
  '--no-sandbox', '--disable-background-networking', '--disable-component-update',
  '--disable-sync', '--no-first-run', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
];

const MIME = {
  '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.mjs': 'text/javascript',
  '.wasm': 'application/wasm', '.json': 'application/json', '.png': 'image/png',
  '.css': 'text/css', '.gltf': 'model/gltf+json', '.glb': 'model/gltf-binary',
  '.bin': 'application/octet-stream', '.hdr': 'application/octet-stream',
};

// Static file server for `dir`, on a free port of 127.0.0.1 only. `extra` maps URL paths to
// files outside `dir` (e.g. a reference image made during the test run).
export function serve(dir, extra = {}) {
  const server = createServer((req, res) => {
    let path = '';
    let pathname = '';
    try {
      pathname = decodeURIComponent(new URL(req.url, 'http://x').pathname);
      path = extra[pathname] || normalize(join(dir, pathname));
    } catch {}  // malformed URL: answered 404 below
    if (pathname.endsWith('/')) path = join(path, 'index.html');
    const inside = extra[pathname] || path.startsWith(dir + sep);
    if (!inside || !statSync(path, { throwIfNoEntry: false })?.isFile()) {
      res.writeHead(404).end('not found');
      return;
    }
    res.writeHead(200, { 'Content-Type': MIME[extname(path)] || 'application/octet-stream',
                         'Cache-Control': 'no-store' });
    res.end(readFileSync(path));
  });
  return new Promise((ok, fail) => {
    server.once('error', fail);
    server.listen(0, '127.0.0.1', () => ok(server));
  });
}

export function closeServer(server) {
  if (!server) return;
  server.closeAllConnections();
  server.close();
}

export function withTimeout(promise, ms, what) {
  let timer;
  const timeout = new Promise((_, fail) => {
    timer = setTimeout(() => fail(new Error(`${what}: no answer in ${ms} ms`)), ms);
  });
  return Promise.race([promise, timeout]).finally(() => clearTimeout(timer));
}

// Launches Chromium with a fresh temporary profile. Returns {context, close()}; close() is
// bounded and removes the profile.
export async function launch({ viewport = { width: 400, height: 420 }, launchMs = 20_000 } = {}) {
  const profile = mkdtempSync(join(tmpdir(), 'penumbra-chromium-'));
  let context;
  try {
    context = await withTimeout(chromium.launchPersistentContext(profile, {
      executablePath: chromiumPath,
      headless: true,
      timeout: launchMs,
      viewport,
      args: CHROMIUM_ARGS,
    }), launchMs + 2_000, 'launch Chromium');
  } catch (e) {
    rmSync(profile, { recursive: true, force: true });
    throw e;
  }
  return {
    context,
    async close() {
      // A wedged browser must not keep the test alive: give close() a bound, then move on
      // (playwright kills the browser process when node exits).
      await withTimeout(context.close(), 10_000, 'browser close').catch(() => {});
      rmSync(profile, { recursive: true, force: true });
    },
  };
}

// Collects a page's console output and uncaught errors, for failure messages.
export function recordConsole(page, lines = []) {
  page.on('console', (m) => lines.push(`[${m.type()}] ${m.text()}`));
  page.on('pageerror', (e) => lines.push(`[pageerror] ${e.message}`));
  return lines;
}
