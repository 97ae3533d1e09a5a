// The path-tracer hand-off page (docs/web/handoff.md, "The path-tracer hand-off"): Penumbra renders and
// converges first; then a path tracer (three-gpu-pathtracer, pathtracer.mjs, in a worker:
// worker.mjs) refines the same view in tiles of a time budget, and the page cross-fades to it
// when the swap rule (swap.mjs) fires; any camera move brings Penumbra back at once. Uses only
// Penumbra's public API: the 'converged' and 'camera' events, viewer.camera, viewer.settings,
// viewer.pause()/resume(), viewer.readPixels({display: true}) and viewer.state.
//
// URL query: scene=URL (a scene .json; default the Cornell box), size=WxH (fixed CSS size of the
// view, else the window), frames=N (Penumbra's m), budget=MS (path tracer per worker animation
// frame, default 50), bounces=N (default 8), tiles=N (N x N tiles per sample; default: chosen from
// the measured sample time so a tile fits the budget),
// maxSamples=N (the path tracer stops there, default 4096), and the rule's factor=F (default 0.5),
// floor=X (default 1/255) and minSamples=N (default 16) (swap.mjs).
// window.handoff holds the state for tests: {phase, samples, checks, swaps, ...}.
import Penumbra from '../lib/penumbra.mjs';
import { RULE_DEFAULTS, agreement, differenceImage, evaluateSwap } from './swap.mjs';

const q = new URLSearchParams(location.search);
const num = (k, d) => (q.has(k) ? Number(q.get(k)) : d);
const sceneUrl = new URL(q.get('scene') || '../assets/cornell_box/cornell_box.json', location.href).href;
const budgetMs = num('budget', 50);
const maxSamples = num('maxSamples', 4096);
const rule = { factor: num('factor', RULE_DEFAULTS.factor), floor: num('floor', RULE_DEFAULTS.floor),
               minSamples: num('minSamples', RULE_DEFAULTS.minSamples) };

const view = document.getElementById('view');
const pcanvas = document.getElementById('canvas');
const tcanvas = document.getElementById('pathtracer');
const status = document.getElementById('status');
if (q.has('size')) {
  const [w, h] = q.get('size').split('x').map(Number);
  Object.assign(view.style, { width: `${w}px`, height: `${h}px` });
}

const state = window.handoff = {
  phase: 'loading',  // loading | penumbra | compiling | tracing | pathtracer | error
  rule, budgetMs, samples: 0, tracingMs: 0, compileMs: null, penumbraFrames: 0,
  checks: [],        // every comparison of the rule since the last camera change
  swaps: [],         // {samples, tracingMs, noise, bias, why, luminance..., ssim} at each swap
  cameraMoves: 0, error: null,
};
let viewer, tracer, penumbraImage = null, previous = null;

function show(phase) {
  state.phase = phase;
  tcanvas.classList.toggle('shown', phase === 'pathtracer');
  const s = state.swaps.at(-1);
  status.textContent = {
    loading: 'loading…',
    compiling: parallelCompile ? 'Penumbra converged; the path tracer is compiling its shader'
                               : 'Penumbra converged; the path tracer is compiling its shader (no background compile in this browser: drawing waits until it is done)',
    penumbra: `Penumbra: frame ${viewer?.state.frame ?? 0} of ${viewer?.state.total ?? 0}`,
    tracing: `Penumbra converged; path tracer: ${state.samples} samples` +
             (state.checks.length ? `, noise ${state.checks.at(-1).noise.toFixed(4)} vs bias ${state.checks.at(-1).bias.toFixed(4)}` : ''),
    pathtracer: `path tracer: ${state.samples} samples (took over at ${s?.samples}: ` +
                `SSIM ${s?.ssim.toFixed(3)}, luminance ${(100 * (s?.relativeLuminanceDifference ?? 0)).toFixed(1)} %)`,
    error: `error: ${state.error}`,
  }[phase];
}

function fail(e) {
  state.error = e && e.message ? e.message : String(e);
  console.error(e);
  show('error');
}

// The path tracer in its worker (worker.mjs, bundled as pathtracer-worker.js): it draws into
// the transferred canvas and answers with samples and snapshots of the displayed image.
class RemoteTracer {
  #worker; #reads = new Map(); #nextRead = 0; generation = 0;
  onCreated = null; onReady = null; onSample = null; onSnapshot = null; onError = null;

  constructor(canvas, init) {
    this.#worker = new Worker(new URL('./pathtracer-worker.js', import.meta.url), { type: 'module' });
    this.#worker.onmessage = ({ data: m }) => this.#receive(m);
    this.#worker.onerror = (e) => this.onError?.(new Error(`path tracer worker: ${e.message || 'failed to load'}`));
    const offscreen = canvas.transferControlToOffscreen();
    this.#worker.postMessage({ type: 'init', canvas: offscreen, ...init }, [offscreen]);
  }

  #receive(m) {
    if (m.type === 'error') this.onError?.(new Error(m.message));
    else if (m.type === 'created') this.onCreated?.(m);
    else if (m.type === 'ready') this.onReady?.(m);
    else if (m.type === 'image') { this.#reads.get(m.id)?.(m.image); this.#reads.delete(m.id); }
    else if (m.generation !== this.generation) return;  // of a view since left
    else if (m.type === 'sample') this.onSample?.(m);
    else if (m.type === 'snapshot') this.onSnapshot?.(m);
  }

  compile(view) { this.#worker.postMessage({ type: 'compile', ...view }); }
  start(view) { this.#worker.postMessage({ type: 'start', generation: ++this.generation, ...view }); }
  stop() { this.generation++; this.#worker.postMessage({ type: 'stop' }); }
  read() {
    const id = this.#nextRead++;
    return new Promise((resolve) => { this.#reads.set(id, resolve); this.#worker.postMessage({ type: 'read', id }); });
  }
}

// The path tracer's shader compiles once per page. With KHR_parallel_shader_compile it compiles
// in the background from the start. Without it (SwiftShader) the compile holds up every WebGL
// call of the page until it is done, Penumbra's too: it starts only once Penumbra has converged,
// and Penumbra is paused meanwhile, so the page's input stays live (a drag moves the camera and
// Penumbra draws the new view when the compile ends) instead of the page freezing on a call.
let parallelCompile = false, compileState = 'no';  // no | running | done

function compile() {
  if (compileState !== 'no') return;
  compileState = 'running';
  state.compileStartedAt = performance.now();
  if (!parallelCompile) viewer.pause();
  tracer.compile({ camera: viewer.camera, width: pcanvas.width, height: pcanvas.height });
}

function compiled(m) {
  compileState = 'done';
  state.compileMs = m.compileMs;
  state.compiledAt = performance.now();
  if (parallelCompile) {
    if (state.phase === 'compiling') beginTracing();
    return;
  }
  viewer.resume();
  // A camera moved during the compile reaches the page with the viewer's next frame: start
  // only if none did.
  requestAnimationFrame(() => requestAnimationFrame(() => {
    if (state.phase === 'compiling') beginTracing();
  }));
}

// Penumbra converged: compare from here on, with the path tracer at Penumbra's exact view.
async function startTracing() {
  penumbraImage = await viewer.readPixels({ display: true });
  state.penumbraFrames = penumbraImage.frames;
  if (pcanvas.width !== penumbraImage.width || pcanvas.height !== penumbraImage.height) {
    throw new Error(`Penumbra rendered ${penumbraImage.width}x${penumbraImage.height} into a ${pcanvas.width}x${pcanvas.height} canvas`);
  }
  if (compileState === 'done') {
    beginTracing();
  } else {
    show('compiling');
    compile();
  }
}

function beginTracing() {
  previous = null;
  state.checks = [];
  state.samples = 0;
  state.tracingMs = 0;
  tracer.start({ camera: viewer.camera, settings: viewer.settings, width: pcanvas.width,
                 height: pcanvas.height, budgetMs, maxSamples });
  show('tracing');
}

function onSample(m) {
  state.samples = m.samples;
  state.tracingMs = m.tracingMs;
  show(state.phase);
}

// At 1, 2, 4, ... samples: keep the snapshot; from minSamples on, apply the rule.
function onSnapshot({ samples, tracingMs, image: current }) {
  if (previous && state.phase === 'tracing') {
    const check = { samples, tracingMs,
                    ...evaluateSwap({ previous, current, penumbra: penumbraImage, samples }, rule) };
    state.checks.push(check);
    if (check.swap) {
      const swap = { ...check, ...agreement(penumbraImage, current) };
      state.swaps.push(swap);
      state.strip = stripDataUrl(penumbraImage, current);
      show('pathtracer');
    }
  }
  previous = current;
}

// Penumbra converged | path tracer at the swap | 4 x |difference|, side by side.
function stripDataUrl(a, b) {
  const d = differenceImage(a, b, 4);
  const c = document.createElement('canvas');
  c.width = a.width * 3;
  c.height = a.height;
  const ctx = c.getContext('2d');
  [a, b, d].forEach((img, k) => {
    const id = ctx.createImageData(img.width, img.height);
    for (let i = 0; i < id.data.length; i++) id.data[i] = Math.round(255 * Math.min(1, Math.max(0, img.data[i])));
    for (let i = 3; i < id.data.length; i += 4) id.data[i] = 255;
    ctx.putImageData(id, k * a.width, 0);
  });
  return c.toDataURL('image/png');
}

// The scene file names the glTF and the environment; a bare glTF gets Penumbra's rule (black
// with lights of its own; the procedural studio otherwise, which the path tracer cannot show).
async function describe(url) {
  const bytes = await fetch(url).then((r) => {
    if (!r.ok) throw new Error(`cannot fetch ${url}: HTTP ${r.status}`);
    return r.text();
  });
  if (!/\.json(\?|$)/.test(new URL(url).pathname)) return { gltfUrl: url, environment: null };
  const s = JSON.parse(bytes);
  const env = s.environment;
  let environment = null;
  if (env && typeof env === 'object' && env.uniform) environment = { uniform: env.uniform };
  else if (env && typeof env === 'object' && env.file) environment = { file: new URL(env.file, url).href };
  else if (typeof env === 'string' && env !== 'none' && env !== 'studio') environment = { file: new URL(env, url).href };
  else if (env === 'none' || env?.preset === 'none') environment = { uniform: [0, 0, 0] };
  return { gltfUrl: new URL(s.gltf, url).href, environment };
}

// For tests and tools: the strip (data URL) of Penumbra's converged image and the path
// tracer's image now.
state.stripNow = async () => (penumbraImage && tracer ? stripDataUrl(penumbraImage, await tracer.read()) : null);

async function main() {
  const frames = q.has('frames') ? { frames: num('frames', 0) } : {};
  // The full size at rest (no adaptive still scale), so both renderers draw the same pixels.
  viewer = await Penumbra.create(pcanvas, { adaptiveResolution: false, pixelRatio: 1, ...frames });
  viewer.on('error', fail);
  const info = await viewer.loadScene(sceneUrl);
  const desc = await describe(sceneUrl);
  let environment = desc.environment;
  if (!environment) {
    if (!info.lights) throw new Error('the hand-off needs a scene file with an environment, or lights of its own (the path tracer has no studio preset)');
    environment = { uniform: [0, 0, 0] };
  }
  // The path tracer's worker loads the scene now, while Penumbra converges.
  tracer = new RemoteTracer(tcanvas, {
    options: { gltfUrl: desc.gltfUrl, environment, settings: viewer.settings,
               bounces: num('bounces', 8), tiles: num('tiles', 0) },
  });
  tracer.onError = fail;
  tracer.onSample = onSample;
  tracer.onSnapshot = onSnapshot;
  tracer.onCreated = (m) => {
    parallelCompile = state.parallelCompile = m.parallelCompile;
    state.lampFaces = m.lampFaces;
    if (parallelCompile) compile();
  };
  tracer.onReady = compiled;
  viewer.on('progress', () => { if (state.phase === 'penumbra') show('penumbra'); });
  viewer.on('converged', () => { startTracing().catch(fail); });
  viewer.on('camera', () => {
    state.cameraMoves++;
    tracer.stop();
    show('penumbra');  // at once, no fade: the path tracer's image is of the old view
  });
  show('penumbra');
  if (viewer.state.converged) await startTracing();
}

main().catch(fail);
