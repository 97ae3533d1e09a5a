// The viewer on weak devices and phones, in Debian's headless Chromium (SwiftShader: slower
// than any phone's GPU, so every frame here is "too slow"):
// - a phone (390x844 CSS pixels, deviceScaleFactor 3, touch): the pixel ratio is capped at 2,
//   the settings panel starts collapsed, an error note fits the screen beside the progress
//   line and a tap dismisses it, a one-finger drag orbits, and the still image's resolution
//   comes from the measured frame cost (screenshots in build-web/test-output/phone-*.png);
// - a tiny time budget splits every frame into bands drawn over several animation frames
//   (state.split > 1), the page keeps its animation frames short, and the converged canvas is
//   the one drawn with whole frames.
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, mkdirSync } from 'node:fs';
import { join } from 'node:path';
import { closeServer, diff, dist, fmt, launch, outDir, pixels, recordConsole, serve,
         withTimeout } from './harness.mjs';

const TEST_MS = 60_000;
const CONVERGE_MS = 40_000;
// The same frames drawn whole or in bands on one GPU: the same bytes (measured: mean 0, max 0).
// One step of 8-bit rounding is allowed in case a driver rounds a scissored clear differently.
const SPLIT_MAX_TOL = 1 / 255;

let server;
const consoleLines = [];

before(async () => {
  mkdirSync(outDir, { recursive: true });
  if (!existsSync(join(dist, 'lib/penumbra_viewer.wasm'))) {
    throw new Error(`${dist}/lib is not built: run tools/build-web first`);
  }
  server = await serve(dist);
});
after(() => closeServer(server));

const url = (query) => `http://127.0.0.1:${server.address().port}/index.html${query}`;

// Opens the page in its own browser (device emulation is per context); returns {browser, page}.
async function open(device, query) {
  const browser = await launch(device);
  try {
    const page = browser.context.pages()[0] || (await browser.context.newPage());
    recordConsole(page, consoleLines);
    await page.goto(url(query), { timeout: 20_000 });
    await page.waitForFunction(() => window.penumbraPage && (window.penumbraPage.ready ||
                                                             window.penumbraPage.fatal),
                               null, { timeout: 30_000 });
    assert.equal(await page.evaluate(() => window.penumbraPage.fatal), undefined);
    return { browser, page };
  } catch (e) {
    await browser.close();
    throw e;
  }
}

const state = (page) => page.evaluate(() => ({ ...window.penumbraPage.viewer.state,
                                               errors: [...window.penumbraPage.errors] }));
const box = (page, sel) => page.locator(sel).first().boundingBox();
const overlaps = (a, b) => a.x < b.x + b.width && b.x < a.x + a.width &&
                           a.y < b.y + b.height && b.y < a.y + a.height;

async function withReport(page, name, body) {
  try {
    await body();
  } catch (e) {
    const shot = join(outDir, `${name}-failed.png`);
    await withTimeout(page.screenshot({ path: shot, timeout: 8_000 }), 10_000, 'screenshot')
      .catch(() => {});
    e.message += `\n--- console ---\n${consoleLines.slice(-30).join('\n')}\n--- screenshot: ${shot}`;
    throw e;
  }
}

test('on a phone: capped pixel ratio, collapsed panel that closes by its control or a tap outside, a note that fits and goes with a tap, touch orbit', { timeout: TEST_MS }, async () => {
  const phone = { viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, isMobile: true,
                  hasTouch: true };
  // A missing environment: the scene renders and a note says what failed.
  // devicePixels=0: the still scale is measured at the first stop, without the sharpening
  // stage that follows it (the last test).
  const { browser, page } = await open(phone, '?frames=8&env=no/such/sky.hdr&devicePixels=0');
  await withReport(page, 'phone', async () => {
    await page.waitForFunction(() => window.penumbraPage.viewer.state.frame >= 1, null,
                               { timeout: 30_000 });
    const s = await state(page);
    assert.equal(s.pixelRatio, 2, 'devicePixelRatio 3 is capped at 2');
    assert.equal(s.canvasWidth, 780);
    assert.equal(s.canvasHeight, 1688);
    assert.equal(await page.isHidden('#panel'), true, 'panel collapsed on a narrow screen');
    const note = page.locator('.message.error');
    assert.equal(await note.count(), 1, `one note: ${s.errors}`);
    assert.match(await note.textContent(), /sky\.hdr/);
    const n = await box(page, '.message.error');
    const hud = await box(page, '#hud');
    assert.ok(n.x >= 0 && n.x + n.width <= 390, `the note fits the width: ${JSON.stringify(n)}`);
    assert.ok(!overlaps(n, hud), `the note leaves the progress line readable: ${JSON.stringify({ n, hud })}`);
    const close = await box(page, '.message.error button');
    assert.ok(close.width >= 32 && close.height >= 32, `a finger-sized close button: ${JSON.stringify(close)}`);
    await page.screenshot({ path: join(outDir, 'phone-note.png') });
    await page.tap('.message.error button');
    assert.equal(await note.count(), 0, 'a tap dismisses the note');

    // One finger drags: the camera moves (accumulation restarts, smaller while moving).
    const cdp = await browser.context.newCDPSession(page);
    const touch = (type, x, y) => cdp.send('Input.dispatchTouchEvent', {
      type, touchPoints: type === 'touchEnd' ? [] : [{ x, y, id: 1 }] });
    const before = await page.evaluate(() => window.penumbraPage.progressLog.length);
    await touch('touchStart', 195, 500);
    const widths = [];
    for (let i = 1; i <= 6; i++) {
      await touch('touchMove', 195 + 10 * i, 500 + 3 * i);
      await page.waitForTimeout(40);
      widths.push((await state(page)).renderWidth);
    }
    await touch('touchEnd');
    const log = await page.evaluate((from) => window.penumbraPage.progressLog.slice(from), before);
    assert.ok(log.includes(1), `the drag restarted accumulation: ${log}`);
    assert.ok(Math.min(...widths) < 780 * (await state(page)).stillScale,
              `smaller while moving: ${widths}`);

    // At rest the still image's scale comes from the measured cost: on SwiftShader a full
    // frame of 780x1688 costs far more than maxSplit x budget, so it is lowered, but never
    // below the canvas's CSS size (390x844).
    await page.waitForFunction(() => window.penumbraPage.convergedCount > 0, null,
                               { timeout: CONVERGE_MS, polling: 100 });
    const still = await state(page);
    assert.deepEqual(still.errors.filter((e) => !/sky\.hdr/.test(e)), []);
    assert.ok(still.msPerMegapixel > 0, 'a cost was measured');
    const fit = Math.sqrt((8 * 12) / (still.msPerMegapixel * 1e-6 * 780 * 1688));
    assert.ok(still.stillScale < 1 && still.stillScale >= 0.5,
              `still scale ${still.stillScale} (fit ${fit.toFixed(2)})`);
    assert.equal(still.renderWidth, Math.round(780 * still.stillScale));
    assert.ok(still.renderWidth >= 390 && still.renderHeight >= 844,
              `at least the CSS size: ${still.renderWidth}x${still.renderHeight}`);
    const read = await page.evaluate(async () => {
      const r = await window.penumbraPage.viewer.readPixels();
      return { width: r.width, canvasWidth: r.canvasWidth, canvasHeight: r.canvasHeight };
    });
    assert.deepEqual(read, { width: still.renderWidth, canvasWidth: 780, canvasHeight: 1688 },
                     'readPixels says its size and the canvas it is shown on');
    const hudAtRest = await box(page, '#hud');
    assert.ok(hudAtRest.x >= 0 && hudAtRest.x + hudAtRest.width <= 390,
              `the progress lines fit the screen: ${JSON.stringify(hudAtRest)}`);
    await page.screenshot({ path: join(outDir, 'phone.png') });
    await page.tap('#toggle-panel');
    assert.equal(await page.isVisible('#panel'), true, 'a tap on Settings opens the panel');
    const p = await box(page, '#panel');
    assert.ok(p.x >= 0 && p.x + p.width <= 390, `the panel fits the width: ${JSON.stringify(p)}`);
    const bar = await box(page, '#toolbar');
    assert.ok(p.y + p.height <= bar.y, `the panel stays above the toolbar: ${JSON.stringify([p, bar])}`);
    await page.screenshot({ path: join(outDir, 'phone-panel.png') });
    // It closes by its own control, and by a tap outside it (on the view).
    const closePanel = await box(page, '#close-panel');
    assert.ok(closePanel.width >= 36 && closePanel.height >= 36, `a finger-sized close control: ${JSON.stringify(closePanel)}`);
    await page.tap('#close-panel');
    assert.equal(await page.isHidden('#panel'), true, 'the close control closes the panel');
    assert.equal(await page.getAttribute('#toggle-panel', 'aria-expanded'), 'false');
    await page.tap('#toggle-panel');
    assert.equal(await page.isVisible('#panel'), true, 'Settings opens it again');
    await page.touchscreen.tap(60, 400);
    assert.equal(await page.isHidden('#panel'), true, 'a tap on the view closes the panel');
  });
  await browser.close();
});

test('on a desktop the still image has every canvas pixel, however slow the device', { timeout: TEST_MS }, async () => {
  const desktop = { viewport: { width: 960, height: 540 }, deviceScaleFactor: 1 };
  const { browser, page } = await open(desktop, '?frames=6');
  await withReport(page, 'desktop-still', async () => {
    // SwiftShader at 960x540: a frame costs several times maxSplit x budget, which used to
    // halve the still resolution; now its parts take longer instead.
    await page.waitForFunction(() => window.penumbraPage.convergedCount > 0, null,
                               { timeout: CONVERGE_MS, polling: 100 });
    const s = await state(page);
    assert.equal(s.pixelRatio, 1);
    assert.equal(s.stillScale, 1);
    assert.deepEqual([s.renderWidth, s.renderHeight], [s.canvasWidth, s.canvasHeight]);
    const r = await page.evaluate(async () => {
      const p = await window.penumbraPage.viewer.readPixels();
      return [p.width, p.height, p.canvasWidth, p.canvasHeight];
    });
    assert.deepEqual(r, [s.canvasWidth, s.canvasHeight, s.canvasWidth, s.canvasHeight]);
  });
  await browser.close();
});

test('a frame slower than the budget is drawn in bands over several animation frames; the image is the same', { timeout: TEST_MS }, async () => {
  const desktop = { viewport: { width: 320, height: 240 } };
  // Whole frames (split=1) vs the default split under a 2 ms budget, adaptation of the
  // resolution off so both render 320x240.
  const base = '?frames=7&pixelRatio=1&panel=0&adaptive=0&budget=2';
  const results = {};
  for (const [name, query] of [['whole', `${base}&split=1`], ['split', base]]) {
    const { browser, page } = await open(desktop, query);
    await withReport(page, `split-${name}`, async () => {
      // Watch every animation frame after frame 2 (the first frames wait for shader
      // compilation on first use): the longest gap is how long input could wait.
      await page.waitForFunction(() => window.penumbraPage.viewer.state.frame >= 2, null,
                                 { timeout: CONVERGE_MS, polling: 20 });
      await page.evaluate(() => {
        const w = (window.__watch = { longest: 0, splits: new Set(), parts: 0, last: performance.now() });
        const tick = () => {
          const now = performance.now();
          w.longest = Math.max(w.longest, now - w.last);
          w.last = now;
          const s = window.penumbraPage.viewer.state;
          w.splits.add(s.split);
          w.parts = Math.max(w.parts, s.parts);
          if (!s.converged) requestAnimationFrame(tick);
        };
        requestAnimationFrame(tick);
      });
      await page.waitForFunction(() => window.penumbraPage.convergedCount > 0 ||
                                       window.penumbraPage.errors.length,
                                 null, { timeout: CONVERGE_MS, polling: 100 });
      const s = await state(page);
      assert.deepEqual(s.errors, []);
      assert.equal(s.frame, 7);
      assert.equal(s.renderWidth, 320);
      const w = await page.evaluate(() => ({ ...window.__watch, splits: [...window.__watch.splits] }));
      results[name] = { ...w, frameMs: s.frameMs, image: await pixels(page) };
    });
    await browser.close();
  }
  const { whole, split } = results;
  console.log(`# whole frames: longest animation frame ${whole.longest.toFixed(0)} ms, ` +
              `last frame ${whole.frameMs.toFixed(0)} ms; split ${split.splits}: longest ` +
              `${split.longest.toFixed(0)} ms, last frame ${split.frameMs.toFixed(0)} ms in up to ` +
              `${split.parts} parts`);
  assert.deepEqual(whole.splits, [1], 'split=1 draws whole frames');
  assert.ok(Math.max(...split.splits) > 1, `the budget split the frames: ${split.splits}`);
  assert.ok(split.parts > Math.max(...split.splits), 'shadow maps are parts of their own');
  // Parts are a fraction of a frame: the page's longest animation frame shrinks with them.
  assert.ok(split.longest < 0.6 * whole.longest,
            `longest animation frame ${split.longest.toFixed(0)} ms split vs ` +
            `${whole.longest.toFixed(0)} ms whole`);
  const d = diff(whole.image, split.image);
  console.log(`# split vs whole frames, converged canvas: ${fmt(d)}`);
  assert.ok(d.max <= SPLIT_MAX_TOL, `split vs whole: ${fmt(d)}`);
});

test('on a phone, a still view done at the CSS size goes on to device pixels and is shown there (sharpened)', { timeout: TEST_MS }, async () => {
  const phone = { viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, isMobile: true,
                  hasTouch: true };
  const { browser, page } = await open(phone, '?frames=8');
  await withReport(page, 'phone-sharpen', async () => {
    await page.evaluate(() => {
      const p = window.penumbraPage;
      p.sharpened = [];
      p.converged = 0;
      p.viewer.on('sharpened', (d) => p.sharpened.push(d));
      p.viewer.on('converged', () => { p.converged++; });
    });
    await page.waitForFunction(() => window.penumbraPage.viewer.state.converged, null,
                               { timeout: CONVERGE_MS });
    const first = await state(page);
    assert.ok(first.renderWidth < first.canvasWidth,
              `done below the drawing buffer first: ${first.renderWidth} of ${first.canvasWidth}`);
    await page.waitForFunction(() => window.penumbraPage.sharpened.length > 0, null,
                               { timeout: CONVERGE_MS * 2 });
    const s = await state(page);
    const got = await page.evaluate(() => ({ sharpened: window.penumbraPage.sharpened,
                                             converged: window.penumbraPage.converged,
                                             status: document.querySelector('#progress').textContent }));
    assert.equal(s.stage, 'device');
    assert.equal(s.renderWidth, s.canvasWidth, 'the still image has every drawing-buffer pixel');
    assert.equal(s.renderHeight, s.canvasHeight);
    assert.equal(got.sharpened.length, 1);
    assert.equal(got.sharpened[0].width, s.canvasWidth);
    assert.ok(got.converged <= 1, `converged keeps its meaning (the first stop): ${got.converged}`);
    assert.match(got.status, /^Done/);
    await page.screenshot({ path: join(outDir, 'phone-sharpened.png') });
  });
  await browser.close();
});

