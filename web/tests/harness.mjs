// Shared pieces of the browser tests and the benchmark: paths, a static file server for
// web/dist on 127.0.0.1, bounded waits, Debian's headless Chromium through playwright-core
// (WebGL2 via ANGLE + SwiftShader; no GPU, display or browser download needed), canvas
// read-back, image differences and the native renders they are compared with.
import { spawnSync } from 'node:child_process';
import { createServer } from 'node:http';
import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { extname, isAbsolute, join, normalize, resolve, sep } from 'node:path';
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
// bounded and removes the profile. Device emulation (deviceScaleFactor, isMobile, hasTouch)
// passes through to playwright.
export async function launch({ viewport = { width: 400, height: 420 }, launchMs = 20_000,
                               ...device } = {}) {
  const profile = mkdtempSync(join(tmpdir(), 'penumbra-chromium-'));
  let context;
  try {
    context = await withTimeout(chromium.launchPersistentContext(profile, {
      executablePath: chromiumPath,
      headless: true,
      timeout: launchMs,
      viewport,
      ...device,
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

// Runs fn(page, browser) in a fresh browser launched with `options` (launch()'s); an error
// carries the page's last 20 console lines, and the browser is closed in any case.
export async function withPage(options, fn) {
  const b = await launch(options);
  const lines = [];
  try {
    const page = b.context.pages()[0] || (await b.context.newPage());
    recordConsole(page, lines);
    return await fn(page, b);
  } catch (e) {
    e.message += `\n${lines.slice(-20).join('\n')}`;
    throw e;
  } finally {
    await withTimeout(b.close(), 15_000, 'close').catch(() => {});
  }
}

// RGBA bytes of the canvas (or of an image URL, or, with `element`, of the canvas in the shadow
// root of the element that selector names: a <penumbra-viewer>), decoded by the browser.
export const pixels = (pg, url, element) => pg.evaluate(async ([src, sel]) => {
  let source = sel ? document.querySelector(sel).shadowRoot.querySelector('canvas')
    : document.getElementById('canvas');
  if (src) {
    source = new Image();
    source.src = src;
    await source.decode();
  }
  const c = document.createElement('canvas');
  c.width = source.width;
  c.height = source.height;
  const ctx = c.getContext('2d');
  ctx.drawImage(source, 0, 0);
  return { width: c.width, height: c.height, data: [...ctx.getImageData(0, 0, c.width, c.height).data] };
}, [url || null, element || null]);

// Mean, max and 99th percentile of |a - b| over R, G, B, in [0, 1].
export function diff(a, b) {
  if (a.width !== b.width || a.height !== b.height) {
    throw new Error(`sizes differ: ${a.width}x${a.height} vs ${b.width}x${b.height}`);
  }
  const hist = new Array(256).fill(0);
  let sum = 0, max = 0, n = 0;
  for (let i = 0; i < a.data.length; i += 4) {
    for (let c = 0; c < 3; c++) {
      const d = Math.abs(a.data[i + c] - b.data[i + c]);
      sum += d;
      max = Math.max(max, d);
      hist[Math.min(255, Math.round(d))]++;
      n++;
    }
  }
  let acc = 0, p99 = 0;
  while (p99 < 255 && (acc += hist[p99]) < 0.99 * n) p99++;
  return { mean: sum / n / 255, max: max / 255, p99: p99 / 255 };
}
export const fmt = (d) => `mean ${d.mean.toFixed(4)}, p99 ${d.p99.toFixed(3)}, max ${d.max.toFixed(3)}`;

// The image averaged over size x size blocks (RGBA, same layout), for noise-robust comparisons.
export function blocks(img, size) {
  const w = Math.floor(img.width / size), h = Math.floor(img.height / size);
  const data = new Array(w * h * 4).fill(0);
  for (let y = 0; y < h * size; y++) {
    for (let x = 0; x < w * size; x++) {
      const o = ((Math.floor(y / size) * w) + Math.floor(x / size)) * 4;
      for (let c = 0; c < 4; c++) data[o + c] += img.data[(y * img.width + x) * 4 + c] / (size * size);
    }
  }
  return { width: w, height: h, data };
}

const NATIVE_BIN = process.env.PENUMBRA_RENDER || join(root, 'build/tools/render/penumbra-render');

function newestSource(dirs) {
  let newest = 0;
  for (const dir of dirs) {
    for (const entry of readdirSync(dir, { recursive: true, withFileTypes: true })) {
      if (entry.isFile()) newest = Math.max(newest, statSync(join(entry.parentPath ?? entry.path, entry.name)).mtimeMs);
    }
  }
  return newest;
}

// The native render of a scene file (path relative to the repository) as {path, source}: made
// now by penumbra-render when it is built and not older than the renderer sources, else
// `golden` (a committed PNG; null when there is none). Notes go to `log`; `args`: more of the
// CLI's flags (e.g. --animation, --time); an absolute `scene` is taken as it is.
export function nativeRender(scene, width, height, frames, outName, golden, log, args = []) {
  const out = join(outDir, outName);
  rmSync(out, { force: true });
  // A CLI older than the renderer sources would compare different code: use the golden then.
  const newest = newestSource([join(root, 'renderer'), join(root, 'glsl')]);
  if (existsSync(NATIVE_BIN) && statSync(NATIVE_BIN).mtimeMs < newest) {
    log.push(`[native] ${NATIVE_BIN} is older than the renderer sources: using the golden`);
  } else if (existsSync(NATIVE_BIN)) {
    const file = isAbsolute(scene) ? scene : join(root, scene);
    const r = spawnSync(NATIVE_BIN, [file, '-o', out, '--size', `${width}x${height}`,
                                     '--frames', String(frames), '-q', ...args],
                        { env: { ...process.env, MESA_GLES_VERSION_OVERRIDE: '3.0' },
                          timeout: 60_000, encoding: 'utf8' });
    if (r.status === 0 && existsSync(out)) return { path: out, source: `${NATIVE_BIN} (this run)` };
    log.push(`[native] penumbra-render failed (${r.status}): ${r.stderr || r.error}`);
  }
  return golden ? { path: golden, source: `golden ${golden}` } : null;
}

// The one-line error of native penumbra-render loading `file` (an absolute path), without the
// program's prefix; null when penumbra-render is not built or is older than the sources.
export function nativeError(file, log) {
  const newest = newestSource([join(root, 'renderer'), join(root, 'glsl')]);
  if (!existsSync(NATIVE_BIN) || statSync(NATIVE_BIN).mtimeMs < newest) {
    log.push(`[native] no current ${NATIVE_BIN}: native error not compared`);
    return null;
  }
  const r = spawnSync(NATIVE_BIN, [file, '-o', join(outDir, 'native-error.png'), '--size', '16x16',
                                   '--frames', '1', '-q'],
                      { env: { ...process.env, MESA_GLES_VERSION_OVERRIDE: '3.0' },
                        timeout: 60_000, encoding: 'utf8' });
  return r.status === 0 ? '' : r.stderr.trim().replace(/^penumbra-render: error: /, '');
}
