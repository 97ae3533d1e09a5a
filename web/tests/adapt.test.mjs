// The viewer's adaptation rules (web/lib/adapt.mjs) in node alone, with made-up frame times:
// pixel ratio cap, bands per frame from the measured cost, the still resolution chosen from
// it (an upper bound kept, a floor, a spike ignored), the motion scale, setting checks.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { ADAPT_DEFAULTS, Adaptation, REFIT_OVER, checkJsSetting, effectivePixelRatio,
  splitSettings }
  from '../lib/adapt.mjs';

const settings = (over = {}) => ({
  budgetMs: 12, resolutionScale: 1, adaptiveResolution: true, maxSplit: 8, ...over,
});
const PHONE = 780 * 1688;  // 390x844 CSS pixels at the capped pixel ratio 2

// Feeds `n` still frames (2, 3, ...) of `ms` each at `pixels`; returns the last frameDone().
function still(a, s, ms, pixels, n = 3, canvasPixels = pixels) {
  let lowered = false;
  for (let i = 0; i < n; i++) {
    lowered = a.frameDone(s, { frame: 2 + i, ms, renderPixels: pixels, canvasPixels,
                               moving: false }) || lowered;
  }
  return lowered;
}

test('the pixel ratio is devicePixelRatio capped at maxPixelRatio (2), unless given', () => {
  assert.equal(effectivePixelRatio({}, 3), 2);
  assert.equal(effectivePixelRatio({}, 1.5), 1.5);
  assert.equal(effectivePixelRatio({ maxPixelRatio: 3 }, 3), 3);
  assert.equal(effectivePixelRatio({ pixelRatio: 1, maxPixelRatio: 2 }, 3), 1);
  assert.equal(effectivePixelRatio({}, undefined), 1);
  assert.equal(ADAPT_DEFAULTS.maxPixelRatio, 2);
});

test('a frame is split into ceil(cost / budget) bands, at most maxSplit', () => {
  const a = new Adaptation();
  const s = settings();
  assert.equal(a.tiles(s, 1e6, { moving: false, frameOne: false }), 8, 'unknown cost: maxSplit');
  assert.equal(a.tiles(s, 1e6, { moving: false, frameOne: true }), 1,
               'frame 1 (environment only) whole until one was measured');
  a.frameDone(s, { frame: 1, ms: 20, renderPixels: 1e6, canvasPixels: 1e6, moving: false });
  assert.equal(a.tiles(s, 1e6, { moving: false, frameOne: true }), 2, 'then from its own cost');
  still(a, s, 30, 1e6);  // 30 ms a frame at 1 Mpx: 3 budgets
  assert.equal(a.msPerPixel(), 30e-6);
  assert.equal(a.tiles(s, 1e6, { moving: false, frameOne: false }), 3);
  assert.equal(a.tiles(s, 0.25e6, { moving: false, frameOne: false }), 1, 'a quarter fits');
  assert.equal(a.tiles(s, 4e6, { moving: false, frameOne: false }), 8, 'capped');
  assert.equal(a.tiles(settings({ maxSplit: 1 }), 4e6, { moving: false, frameOne: false }), 1);
  assert.equal(a.tiles(s, 1e6, { moving: true, frameOne: true }), 1,
               'frame 1 while moving must show in the same animation frame');
  assert.equal(a.tiles(s, 1e6, { moving: true, frameOne: false }), 3);
});

test('the still scale stays full on a fast device and follows the cost on a slow one', () => {
  const s = settings();
  const fast = new Adaptation();
  fast.cssScale = 0.5;
  assert.equal(fast.refit(s, PHONE), 0.5, 'nothing measured yet: the floor (the CSS size)');
  still(fast, s, 40, PHONE);  // under maxSplit x budget = 96 ms
  assert.equal(fast.refit(s, PHONE), 1);

  const slow = new Adaptation();
  slow.stillScale = 1;  // as if chosen at full scale
  // 250 ms a full frame: fits 96 ms at sqrt(96 / 250) = 0.62 -> 0.60 in 5 % steps.
  assert.equal(still(slow, s, 250, PHONE, 1), true, 'over 1.5 x 96 ms: lowered at once');
  assert.equal(slow.stillScale, 0.6);
  assert.equal(slow.currentStillScale(s), 0.6);
  // Measured again at 0.6 (0.36 of the pixels): the same cost per pixel, no change.
  assert.equal(still(slow, s, 90, Math.round(PHONE * 0.36), 3, PHONE), false);
  assert.equal(slow.refit(s, PHONE), 0.6);
  // A larger budget or maxSplit lets it rise again at the next rest, up to resolutionScale.
  assert.equal(slow.refit(settings({ budgetMs: 40 }), PHONE), 1);
  assert.equal(slow.refit(settings({ budgetMs: 40, resolutionScale: 0.75 }), PHONE), 0.75);
});

test('the still scale has a floor (minStillScale), and resolutionScale stays an upper bound', () => {
  const s = settings();
  const a = new Adaptation();
  still(a, s, 3000, PHONE);  // SwiftShader-slow: fit 0.18
  assert.equal(a.refit(s, PHONE), ADAPT_DEFAULTS.minStillScale);
  const b = new Adaptation({ minStillScale: 0.25 });
  still(b, s, 3000, PHONE);
  assert.equal(b.refit(s, PHONE), 0.25);
  // A user's resolutionScale below the floor wins: adaptation never raises it.
  assert.equal(a.refit(settings({ resolutionScale: 0.3 }), PHONE), 0.3);
  // Off: always resolutionScale, whatever the cost.
  assert.equal(a.refit(settings({ adaptiveResolution: false }), PHONE), 1);
  assert.equal(a.frameDone(settings({ adaptiveResolution: false }),
                           { frame: 5, ms: 9000, renderPixels: PHONE, canvasPixels: PHONE,
                             moving: false }), false);
});

test('the still image never drops below the canvas CSS size (cssScale)', () => {
  const s = settings();
  const desktop = new Adaptation();
  desktop.cssScale = 1;  // pixel ratio 1: every drawing-buffer pixel is a CSS pixel
  still(desktop, s, 3000, 1366 * 768);  // SwiftShader-slow: would fit 0.18
  assert.equal(desktop.refit(s, 1366 * 768), 1, 'a desktop keeps every pixel');
  assert.equal(still(desktop, s, 3000, 1366 * 768), false, 'and is never lowered');
  const phone = new Adaptation();
  phone.cssScale = 0.5;  // pixel ratio 2: the CSS size is half the buffer
  still(phone, s, 3000, PHONE);
  assert.equal(phone.refit(s, PHONE), 0.5);
  const laptop = new Adaptation();
  laptop.cssScale = 0.8;  // pixel ratio 1.25
  still(laptop, s, 3000, PHONE);
  assert.equal(laptop.refit(s, PHONE), 0.8);
  // Where it affords more, more (device pixels as far as the budget allows).
  const fast = new Adaptation();
  fast.cssScale = 0.5;
  still(fast, s, 150, PHONE);  // fits 96 ms at 0.8
  assert.equal(fast.refit(s, PHONE), 0.8);
  // A user's resolutionScale below the CSS size still wins.
  assert.equal(desktop.refit(settings({ resolutionScale: 0.5 }), 1366 * 768), 0.5);
});

test('lowering during convergence needs more than 1.5 x maxSplit budgets; one spike is ignored', () => {
  const s = settings();
  const limit = s.maxSplit * s.budgetMs;
  const a = new Adaptation();
  a.stillScale = 1;  // chosen at full scale (a rest after frames were measured)
  assert.equal(still(a, s, limit * 1.2, 1e6, 3), false, 'slightly over: wait for the next rest');
  assert.equal(a.currentStillScale(s), 1);
  assert.ok(a.refit(s, 1e6) < 1, 'at the next rest it fits the budget');

  const b = new Adaptation();
  b.stillScale = 1;
  still(b, s, 50, 1e6, 2);
  const spike = b.frameDone(s, { frame: 4, ms: limit * REFIT_OVER * 3, renderPixels: 1e6,
                                 canvasPixels: 1e6, moving: false });
  assert.equal(spike, false, 'the median of three ignores one slow frame');
  assert.equal(b.currentStillScale(s), 1);
  // Frames while moving and frame 1 are not costs of the still image.
  const c = new Adaptation();
  c.frameDone(s, { frame: 3, ms: 5000, renderPixels: 1e6, canvasPixels: 1e6, moving: true });
  c.frameDone(s, { frame: 1, ms: 5000, renderPixels: 1e6, canvasPixels: 1e6, moving: false });
  assert.equal(c.msPerPixel(), null, 'moving frames and frame 1 are not still costs');
  // A new scene forgets the cost and the chosen scale.
  still(c, s, 3000, 1e6);
  assert.ok(c.refit(s, 1e6) < 1);
  c.reset();
  assert.equal(c.msPerPixel(), null);
  assert.equal(c.currentStillScale(s), 1);
});

test('frame 1 over budget while moving shrinks the motion scale (floor minMotionScale); fast grows it', () => {
  const s = settings();
  const a = new Adaptation();
  a.frameDone(s, { frame: 1, ms: 48, renderPixels: 1e6, canvasPixels: 1e6, moving: true });
  assert.ok(Math.abs(a.motionScale - Math.sqrt(12 / 48) * 0.9) < 1e-12);
  for (let i = 0; i < 10; i++) {
    a.frameDone(s, { frame: 1, ms: 1000, renderPixels: 1e6, canvasPixels: 1e6, moving: true });
  }
  assert.equal(a.motionScale, ADAPT_DEFAULTS.minMotionScale);
  a.frameDone(s, { frame: 1, ms: 2, renderPixels: 1e6, canvasPixels: 1e6, moving: true });
  assert.ok(Math.abs(a.motionScale - 0.25 * 1.15) < 1e-12);
  const still1 = a.motionScale;
  a.frameDone(s, { frame: 1, ms: 1000, renderPixels: 1e6, canvasPixels: 1e6, moving: false });
  assert.equal(a.motionScale, still1, 'frame 1 of a still image leaves it');

  // A gesture starts from what the last frame 1 predicts: 48 ms at 1 Mpx -> 0.45 of the side.
  const b = new Adaptation();
  b.startMotion(s, 1e6);
  assert.equal(b.motionScale, 1, 'nothing measured: unchanged');
  b.frameDone(s, { frame: 1, ms: 48, renderPixels: 1e6, canvasPixels: 1e6, moving: false });
  b.startMotion(s, 1e6);
  assert.ok(Math.abs(b.motionScale - 0.5 * 0.9) < 1e-12, `${b.motionScale}`);
  b.frameDone(s, { frame: 1, ms: 2, renderPixels: 1e6, canvasPixels: 1e6, moving: false });
  b.startMotion(s, 1e6);
  assert.ok(Math.abs(b.motionScale - 0.45) < 1e-12, 'it only lowers; growing is per frame');
});

test('the JS settings are checked with one-line messages', () => {
  assert.equal(checkJsSetting('maxSplit', 4), null);
  assert.equal(checkJsSetting('maxSplit', 0), "setting 'maxSplit' must be an integer in 1..64");
  assert.equal(checkJsSetting('maxSplit', 2.5), "setting 'maxSplit' must be an integer in 1..64");
  assert.equal(checkJsSetting('budgetMs', 0), "setting 'budgetMs' must be in (0, 1000]");
  assert.equal(checkJsSetting('budgetMs', 1000), null);
  assert.equal(checkJsSetting('resolutionScale', 3), "setting 'resolutionScale' must be in [0.1, 2]");
  assert.equal(checkJsSetting('adaptiveResolution', 1),
               "setting 'adaptiveResolution' must be true or false");
  assert.equal(checkJsSetting('adaptiveResolution', false), null);
  assert.equal(checkJsSetting('nope', 1), "unknown setting 'nope'");
});

test('setSettings splits renderer and JS settings, checks JS values, names an unknown key', () => {
  const wasmKeys = new Set(['exposure', 'frames']);
  assert.deepEqual(splitSettings({ exposure: 1, budgetMs: 20, frames: undefined }, wasmKeys),
                   { wasm: { exposure: 1 }, js: { budgetMs: 20 } });
  assert.equal(splitSettings({ nonsense: 1 }, wasmKeys).error, "unknown setting 'nonsense'");
  assert.equal(splitSettings({ budgetMs: -1 }, wasmKeys).error, checkJsSetting('budgetMs', -1));
});

test('update: a gesture beginning fits the motion scale to frame 1, once a gesture', () => {
  const a = new Adaptation();
  const s = settings();
  // Frame 1 at 4x the budget: a gesture's motion scale fits it at once.
  a.frameDone(s, { frame: 1, ms: 48, renderPixels: PHONE, canvasPixels: PHONE, moving: false });
  a.update(s, PHONE, true);
  assert.ok(a.motionScale < 0.6, `motion scale ${a.motionScale}`);
  const motion = a.motionScale;
  a.update(s, PHONE, true);  // the same gesture: no new fit
  assert.equal(a.motionScale, motion);
});
