// Browser smoke test: serves web/dist on 127.0.0.1, opens smoke/index.html in Debian's headless
// Chromium (WebGL2 through ANGLE + SwiftShader) and checks what the wasm module read back from
// float render targets. Every wait is bounded so a misbehaving browser fails the test instead
// of hanging it. The page's screenshot and result go to build-web/test-output/.
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { createServer } from 'node:http';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, statSync,
         writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const root = resolve(fileURLToPath(new URL('../..', import.meta.url)));
const dist = resolve(process.env.PENUMBRA_WEB_DIST || join(root, 'web/dist'));
const outDir = resolve(process.env.PENUMBRA_TEST_OUTPUT || join(root, 'build-web/test-output'));
const shot = join(outDir, 'smoke.png');
const chromiumPath = process.env.PENUMBRA_CHROMIUM || '/usr/lib/chromium/chromium';
// Worst case: load + result + screenshot + close bounds (60 s), plus playwright's own 30 s
// graceful-close-then-kill of a wedged browser, stays under tools/test-web's outer 115 s kill.
// A healthy run takes about 4 s.
const LAUNCH_MS = 20_000;
const LOAD_MS = 15_000;
const RESULT_MS = 25_000;

const MIME = {
  '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.mjs': 'text/javascript',
  '.wasm': 'application/wasm', '.json': 'application/json', '.png': 'image/png',
};

// Static file server for `dist`, on a free port of 127.0.0.1 only.
function serve(dir) {
  const server = createServer((req, res) => {
    let path = '';
    try {
      path = normalize(join(dir, decodeURIComponent(new URL(req.url, 'http://x').pathname)));
    } catch {}  // malformed URL: answered 404 below
    if (!path.startsWith(dir + sep) || !statSync(path, { throwIfNoEntry: false })?.isFile()) {
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

function withTimeout(promise, ms, what) {
  let timer;
  const timeout = new Promise((_, fail) => {
    timer = setTimeout(() => fail(new Error(`${what}: no answer in ${ms} ms`)), ms);
  });
  return Promise.race([promise, timeout]).finally(() => clearTimeout(timer));
}

let server, context, profile, page;
let result;           // window.smokeResult, or undefined when the page never produced one
let setupError;       // why not, with the page's console output
const consoleLines = [];

before(async () => {
  mkdirSync(outDir, { recursive: true });
  rmSync(shot, { force: true });  // never leave a stale screenshot to mislead
  if (!existsSync(join(dist, 'smoke/penumbra_smoke.wasm'))) {
    setupError = new Error(`${dist}/smoke is not built: run tools/build-web first`);
    return;
  }
  server = await serve(dist);
  profile = mkdtempSync(join(tmpdir(), 'penumbra-chromium-'));
  try {
    context = await withTimeout(chromium.launchPersistentContext(profile, {
      executablePath: chromiumPath,
      headless: true,
      timeout: LAUNCH_MS,
      viewport: { width: 400, height: 420 },
      args: ['--no-sandbox', '--disable-background-networking', '--disable-component-update',
             '--disable-sync', '--no-first-run', '--enable-unsafe-swiftshader',
             '--use-angle=swiftshader'],
    }), LAUNCH_MS + 2_000, 'launch Chromium');
    page = context.pages()[0] || (await withTimeout(context.newPage(), 5_000, 'new page'));
    page.on('console', (m) => consoleLines.push(`[${m.type()}] ${m.text()}`));
    page.on('pageerror', (e) => consoleLines.push(`[pageerror] ${e.message}`));
    const url = `http://127.0.0.1:${server.address().port}/smoke/index.html`;
    await page.goto(url, { timeout: LOAD_MS });
    await page.waitForFunction(() => window.smokeResult !== undefined, null, { timeout: RESULT_MS });
    result = await withTimeout(page.evaluate(() => window.smokeResult), 5_000, 'read result');
    writeFileSync(join(outDir, 'smoke-result.json'), JSON.stringify(result, null, 2));
  } catch (e) {
    setupError = e;
  }
  if (page) {
    await withTimeout(page.screenshot({ path: shot, timeout: 8_000 }),
                      10_000, 'screenshot').catch((e) => consoleLines.push(`[screenshot] ${e}`));
  }
}, { timeout: 95_000 });

after(async () => {
  // A wedged browser must not keep the test alive: give close() a bound, then move on
  // (playwright kills the browser process when node exits).
  if (context) await withTimeout(context.close(), 10_000, 'browser close').catch(() => {});
  if (server) { server.closeAllConnections(); server.close(); }
  if (profile) rmSync(profile, { recursive: true, force: true });
});

// The page's result for one run, or a failure that says why there is none.
function run(name) {
  const why = (msg) => `${msg}\n--- page console ---\n${consoleLines.join('\n')}\n` +
                       (existsSync(shot) ? `--- screenshot: ${shot}` : '--- no screenshot');
  if (setupError) assert.fail(why(`smoke page did not finish: ${setupError.message}`));
  if (result.error) assert.fail(why(`smoke page failed: ${result.error}`));
  const r = result[name];
  assert.ok(r, why(`no '${name}' result`));
  if (r.error) assert.fail(why(`${name}: ${r.error}`));
  return r;
}

test('context is WebGL2 through the platform layer', () => {
  const r = run('full');
  assert.equal(r.backend, 'webgl2');
  assert.match(r.context, /^WebGL2: .*WebGL 2\.0/);
});

test('capability report lists the float extensions', () => {
  const r = run('full');
  for (const ext of ['EXT_color_buffer_float', 'OES_texture_float_linear', 'EXT_float_blend']) {
    assert.ok(r.extensions.includes(ext), `${ext} missing from ${r.extensions.join(' ')}`);
  }
  assert.equal(r.colorBufferFloat, true);
  assert.equal(r.colorBufferHalfFloat, true);
  assert.equal(r.floatLinear, true);
  assert.equal(r.floatBlend, true);
  assert.match(r.report, /RGBA32F renderable: yes/);
  assert.match(r.report, /float linear filtering: yes/);
  assert.match(r.report, /float blending: yes/);
});

test('RGBA32F target reads back the cleared values exactly', () => {
  const r = run('full');
  assert.equal(r.format, 'RGBA32F');
  assert.deepEqual(r.values, [0.25, 0.5, 1.5, 2.0]);
  assert.equal(r.uniform, true, 'every pixel of the target holds the clear value');
});

test('forced half-float fallback reads back within half precision', () => {
  const r = run('half');
  assert.equal(r.format, 'RGBA16F');
  assert.match(r.report, /fallback: RGBA16F accumulation \(forced\)/);
  const expected = [0.125, -0.75, 3.5, 2048.0];
  r.values.forEach((v, i) => {
    // float16 keeps 11 significant bits: relative error at most 2^-11 after rounding.
    const tol = Math.abs(expected[i]) * 2 ** -11;
    assert.ok(Math.abs(v - expected[i]) <= tol, `channel ${i}: ${v} vs ${expected[i]}`);
  });
  assert.equal(r.uniform, true, 'every pixel of the target holds the clear value');
});

test('C++ exceptions are caught inside wasm (-fexceptions)', () => {
  const r = run('exceptions');
  assert.match(r.caught, /parse error/);
});
