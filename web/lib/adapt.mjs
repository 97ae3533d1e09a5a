// How the viewer adapts to the device (web/lib/penumbra.mjs runs it; docs/web/viewer.md, "Adapting
// to the device", states the rules). Plain arithmetic on measured times, no wasm or DOM, so
// web/tests/adapt.test.mjs checks it in node.
//
// - Pixel ratio: the canvas's drawing buffer is its CSS size x min(devicePixelRatio,
//   maxPixelRatio) unless pixelRatio is given.
// - Cost: what a full intermediate frame (any frame but frame 1, which is environment only)
//   costs per render pixel, measured with the camera still: the median of the last three.
//   Frame 1 is predicted from the last frame 1.
// - Split: a frame is drawn in k = ceil(predicted cost / budget) bands, 1 <= k <= maxSplit,
//   so one part fits the time budget of an animation frame; with nothing measured, frame 1 is
//   whole (the first image comes soonest) and later frames take maxSplit. While the camera
//   moves, frame 1 is never split: it must show in the animation frame that handled the input.
// - Still scale: the largest scale whose predicted frame cost fits maxSplit budgets, in 5 %
//   steps between a floor and resolutionScale (the floor before any cost is known); chosen
//   when the camera comes to rest (and on a new scene, canvas size or setting), and
//   lowered at once when a still frame costs more than 1.5 x maxSplit budgets. The floor is
//   the canvas's CSS size (cssScale = 1 / pixel ratio: every pixel on a desktop, the CSS
//   pixels of a high-DPR phone) or minStillScale if higher, and never above resolutionScale:
//   a still image is not shown below the page's own resolution. (Its frames keep at most
//   maxSplit parts: each band redraws the geometry, so more parts cost a heavy model more
//   than they save; a slow device's parts then take longer than the budget.)
// - Motion scale: when a gesture begins, at most the scale at which the last frame 1 predicts
//   a frame 1 within the budget (x 0.9); while moving, frame 1 over budget shrinks it by
//   sqrt(budget / time) x 0.9 (floor minMotionScale); under 40 % of the budget it grows by 15 %.

export const ADAPT_DEFAULTS = {
  budgetMs: 12,             // time per animation frame spent on intermediate frames
  resolutionScale: 1,       // render / canvas resolution when still: an upper bound
  adaptiveResolution: true, // the still resolution follows the measured frame cost
  maxSplit: 8,              // most parts (bands) a frame is split into to fit the budget
  maxPixelRatio: 2,         // caps devicePixelRatio (phones have 3: 2.25x the pixels of 2)
  minStillScale: 0.5,       // the lowest resolution scale adaptation picks for the still image
  minMotionScale: 0.25,     // the lowest resolution scale used while the camera moves
  devicePixels: true,       // a still view done below the drawing buffer's pixels goes on to them
};

// The viewer's own settings (setSettings() takes them next to the renderer's schema).
export const JS_SCHEMA = [
  { key: 'budgetMs', type: 'number', min: 0, max: 1000, default: ADAPT_DEFAULTS.budgetMs,
    viewer: true, range: '(0, 1000]',
    help: 'milliseconds per animation frame spent on intermediate frames' },
  { key: 'resolutionScale', type: 'number', min: 0.1, max: 2,
    default: ADAPT_DEFAULTS.resolutionScale, viewer: true, range: '[0.1, 2]',
    help: 'render resolution / canvas resolution when the camera is still (an upper bound)' },
  { key: 'adaptiveResolution', type: 'bool', default: ADAPT_DEFAULTS.adaptiveResolution,
    viewer: true, range: 'true or false',
    help: 'lower the still resolution when a frame costs more than maxSplit budgets' },
  { key: 'maxSplit', type: 'integer', min: 1, max: 64, default: ADAPT_DEFAULTS.maxSplit,
    viewer: true, range: '1..64',
    help: 'most parts a frame is split into to fit the budget (1: never split)' },
  { key: 'devicePixels', type: 'bool', default: ADAPT_DEFAULTS.devicePixels, viewer: true,
    range: 'true or false',
    help: 'a still view done at the CSS size goes on to the drawing buffer\'s (device) pixels, ' +
          'shown when done there (the sharpened event)' },
];

// null when `v` is a valid value of JS setting `key`, else the one-line message.
export function checkJsSetting(key, v) {
  const e = JS_SCHEMA.find((x) => x.key === key);
  if (!e) return `unknown setting '${key}'`;
  const ok = e.type === 'bool' ? typeof v === 'boolean'
    : typeof v === 'number' && (e.type !== 'integer' || Number.isInteger(v)) && v <= e.max &&
      (e.range.startsWith('(') ? v > e.min : v >= e.min);
  if (ok) return null;
  const what = e.type === 'integer' ? 'an integer in ' : e.type === 'bool' ? '' : 'in ';
  return `setting '${key}' must be ${what}${e.range}`;
}

// setSettings()'s changes split into the renderer's (`wasmKeys`) and the JS side's, each JS
// value checked: {wasm, js} or {error} (the first bad key's message). Undefined values skip.
export function splitSettings(changes, wasmKeys) {
  const wasm = {}, js = {};
  for (const [k, v] of Object.entries(changes)) {
    if (v === undefined) continue;
    if (wasmKeys.has(k)) wasm[k] = v;
    else if (JS_SCHEMA.some((e) => e.key === k)) js[k] = v;
    else return { error: `unknown setting '${k}'` };
  }
  for (const [k, v] of Object.entries(js)) {
    const bad = checkJsSetting(k, v);
    if (bad) return { error: bad };
  }
  return { wasm, js };
}

// A still frame this much over its maxSplit budgets lowers the scale at once (restart);
// below it, a new scale waits for the next rest. The margin keeps noise from restarting.
export const REFIT_OVER = 1.5;
const COSTS_KEPT = 3;
const SCALE_STEP = 0.05;

export function effectivePixelRatio({ pixelRatio, maxPixelRatio }, devicePixelRatio) {
  if (pixelRatio !== undefined) return pixelRatio;
  return Math.min(devicePixelRatio || 1, maxPixelRatio ?? ADAPT_DEFAULTS.maxPixelRatio);
}

export class Adaptation {
  motionScale = 1;
  // The render scale at which the image has the canvas's CSS size (1 / pixel ratio); the still
  // scale's floor. 0: none (node tests that leave it out).
  cssScale = 0;
  stillScale = null;  // null until the first choice: resolutionScale
  #costs = [];        // ms per render pixel of the last still frames (n >= 2)
  #frame1 = null;     // ms per render pixel of the last frame 1
  #opts;
  #wasMoving = false; #refitDue = true;  // update(): choose the still scale at the next rest

  constructor(options = {}) {
    this.#opts = { ...ADAPT_DEFAULTS, ...options };
  }

  // Forgets measured costs and the still scale chosen from them (another scene or a new
  // context costs differently): full scale until frames say otherwise.
  reset() {
    this.#costs = [];
    this.#frame1 = null;
    this.stillScale = null;
    this.#refitDue = true;
  }

  // The canvas's pixels or the JS settings changed: choose the still scale again at rest.
  refitLater() { this.#refitDue = true; }

  // Each animation frame of the viewer: a gesture beginning fits the motion scale to the
  // budget; at rest (again, or after refitLater) the still scale is chosen from what frames
  // cost here.
  update(settings, canvasPixels, moving) {
    if (moving) {
      if (!this.#wasMoving) this.startMotion(settings, canvasPixels);
      this.#wasMoving = true;
    } else if (this.#wasMoving || this.#refitDue) {
      this.#wasMoving = false;
      this.#refitDue = false;
      this.refit(settings, canvasPixels);
    }
  }

  // Median ms per render pixel of the last still frames, or null before any was measured.
  msPerPixel() {
    if (!this.#costs.length) return null;
    const s = [...this.#costs].sort((a, b) => a - b);
    return s[(s.length - 1) >> 1];
  }

  // The still image's resolution scale for a canvas of `canvasPixels` (settings: budgetMs,
  // resolutionScale, adaptiveResolution, maxSplit).
  fitStillScale(settings, canvasPixels) {
    const cap = settings.resolutionScale;
    const cost = this.msPerPixel();
    if (!settings.adaptiveResolution || !(canvasPixels > 0)) return cap;
    const floor = Math.min(Math.max(this.#opts.minStillScale, this.cssScale), cap);
    // Nothing measured (a new scene): the floor, which the first frames can never lower, so a
    // load starts once; device pixels beyond it come at the next rest, once measured.
    if (cost === null) return floor;
    const fit = Math.sqrt((settings.maxSplit * settings.budgetMs) / (cost * canvasPixels));
    const stepped = Math.floor(fit / SCALE_STEP + 1e-9) * SCALE_STEP;
    return Math.min(cap, Math.max(floor, Number(stepped.toFixed(2))));
  }

  // Chooses the still scale now (the camera came to rest, a scene loaded, ...).
  refit(settings, canvasPixels) {
    this.stillScale = this.fitStillScale(settings, canvasPixels);
    return this.stillScale;
  }

  currentStillScale(settings) {
    return this.stillScale === null ? settings.resolutionScale
                                    : Math.min(this.stillScale, settings.resolutionScale);
  }

  // Bands for the frame about to begin at `renderPixels`; frameOne: it is frame 1.
  tiles(settings, renderPixels, { moving, frameOne }) {
    if (settings.maxSplit <= 1 || (moving && frameOne)) return 1;
    const cost = frameOne ? this.#frame1 : this.msPerPixel();
    if (cost === null) return frameOne ? 1 : settings.maxSplit;  // frame 1 is the cheap one
    const k = Math.ceil((cost * renderPixels) / settings.budgetMs);
    return Math.min(settings.maxSplit, Math.max(1, k));
  }

  // A frame completed: frame n took `ms` (its parts' time) at `renderPixels`. Returns true
  // when the still scale was lowered (the caller restarts at the new size).
  frameDone(settings, { frame, ms, renderPixels, canvasPixels, moving }) {
    if (frame === 1) {
      if (renderPixels > 0) this.#frame1 = ms / renderPixels;
      if (moving) this.#adaptMotion(ms, settings);
      return false;
    }
    if (moving || !(renderPixels > 0)) return false;
    this.#costs.push(ms / renderPixels);
    if (this.#costs.length > COSTS_KEPT) this.#costs.shift();
    if (!settings.adaptiveResolution) return false;
    const predicted = this.msPerPixel() * renderPixels;
    if (predicted <= REFIT_OVER * settings.maxSplit * settings.budgetMs) return false;
    const current = this.currentStillScale(settings);
    const lower = this.fitStillScale(settings, canvasPixels);
    if (lower >= current - 1e-9) return false;
    this.stillScale = lower;
    return true;
  }

  // A gesture begins: the first preview should already fit the budget.
  startMotion(settings, canvasPixels) {
    if (this.#frame1 === null || !(canvasPixels > 0)) return;
    const fit = Math.sqrt(settings.budgetMs / (this.#frame1 * canvasPixels)) * 0.9;
    const floor = Math.min(this.#opts.minMotionScale, settings.resolutionScale);
    this.motionScale = Math.max(floor, Math.min(this.motionScale, fit));
  }

  // Frame 1 over budget while moving: shrink the area in proportion (with 10 % headroom); well
  // under budget: grow back. Learned across gestures; the still image has its own scale.
  #adaptMotion(frame1Ms, settings) {
    const budget = settings.budgetMs;
    const floor = Math.min(this.#opts.minMotionScale, settings.resolutionScale);
    if (frame1Ms > budget) {
      this.motionScale = Math.max(floor, this.motionScale * Math.sqrt(budget / frame1Ms) * 0.9);
    } else if (frame1Ms < budget * 0.4) {
      this.motionScale = Math.min(1, this.motionScale * 1.15);
    }
  }
}
