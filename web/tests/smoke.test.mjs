// Browser smoke test: serves web/dist on 127.0.0.1, opens smoke/index.html in Debian's headless
// Chromium (WebGL2 through ANGLE + SwiftShader) and checks what the wasm module read back from
// float render targets. Every wait is bounded so a misbehaving browser fails the test instead
// of hanging it. The page's screenshot and result go to build-web/test-output/.
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { closeServer, dist, launch, outDir, recordConsole, serve, withTimeout } from './harness.mjs';

const shot = join(outDir, 'smoke.png');
// Worst case: load + result + screenshot + close bounds (60 s), plus playwright's own 30 s
// graceful-close-then-kill of a wedged browser, stays under tools/test-web's outer kill.
// A healthy run takes about 4 s.
const LAUNCH_MS = 20_000;
const LOAD_MS = 15_000;
const RESULT_MS = 25_000;

let server, browser, page;
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
  try {
    browser = await launch({ viewport: { width: 400, height: 420 }, launchMs: LAUNCH_MS });
    page = browser.context.pages()[0] ||
           (await withTimeout(browser.context.newPage(), 5_000, 'new page'));
    recordConsole(page, consoleLines);
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
  if (browser) await browser.close();
  closeServer(server);
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
