// Penumbra's JavaScript API: a progressive physically-based viewer on a <canvas>.
//
//   import Penumbra from './lib/penumbra.mjs';
//   const viewer = await Penumbra.create(canvas, { budgetMs: 12 });
//   await viewer.loadScene('assets/cornell_box/cornell_box.json');
//   viewer.on('progress', ({ frame, total }) => ...);
//
// The wasm module (penumbra_viewer.js/.wasm, the same C++ and GLSL as the native renderer)
// draws cheap intermediate frames and accumulates them. This file owns the frame loop: on each
// requestAnimationFrame it draws as many frames, or parts of a slow frame, as fit the time
// budget, timing each with a 1-pixel read-back (glFinish does not block in WebGL), then
// tone-maps the accumulation into the canvas. A camera change restarts at frame 1; adapt.mjs
// chooses the resolution (lower while moving) and the split from measured costs.
//
// Every method that can fail returns a promise that rejects with a PenumbraError whose message
// is the one-line C++ message; nothing throws out of the frame loop or the event handlers
// (failures there go to the 'error' event). docs/web/api.md documents the API.
import createPenumbraViewerModule from './penumbra_viewer.js';
import { ADAPT_DEFAULTS, Adaptation, JS_SCHEMA, checkJsSetting, effectivePixelRatio } from './adapt.mjs';
import { provideDecoders } from './decoders.mjs';
import { bindWasmApi, decodeInSteps, timeSteps } from './wasm_api.mjs';
import { OrbitCamera, attachOrbitControls } from './orbit.mjs';
import { FrameLoop } from './loop.mjs';
import { AutoRotate } from './autorotate.mjs';
import { PenumbraError, STEPPED_PANORAMA_PIXELS, fetchBytes, gatherScene, panoramaTooLarge,
  radianceSize, sourceName, toBytes } from './staging.mjs';
import { version } from './version.mjs';  // written by CMake from the project's version

export { PenumbraError, version };

const DEFAULTS = {
  ...ADAPT_DEFAULTS,     // budgetMs, resolutionScale, adaptiveResolution, maxSplit, ...
  stillMs: 200,          // the camera counts as still this long after the last change
  forceHalfFloat: false, // accumulate in RGBA16F (the weak-device path) even where RGBA32F works
  controls: true,        // orbit/pan/zoom with mouse and touch
  autoResize: true,      // keep the canvas's drawing buffer at its CSS size x pixelRatio
  pixelRatio: undefined, // default: min(devicePixelRatio, maxPixelRatio)
};
// The renderer's settings come from the settings schema in the wasm module (one table in C++,
// penumbra/settings.h); JS_SCHEMA (adapt.mjs) holds the JS side's own.
const JS_SETTINGS = new Set(JS_SCHEMA.map((e) => e.key));

// The device-pixel stage begins this long after the first stop (#device).
const DEVICE_STAGE_DELAY_MS = 1000;

let canvasIds = 0;
let stagingIds = 0;

export class Viewer {
  #mod; #pv; #canvas; #opts; #listeners = new Map();
  #schema = []; #wasmKeys = new Set();  // the settings schema; keys setSettings() sends to wasm
  #overrides = {};             // wasm settings the user set (re-applied after loads/restores)
  #jsSettings;                 // budgetMs, resolutionScale, adaptiveResolution, maxSplit
  #orbit = null; #controls = null; #cameraDirty = false; #lastChange = -Infinity;
  #autoRotate = new AutoRotate();  // autorotate.mjs: turns the orbit once left alone
  #cameraSource = 'user-interaction';  // what moved the orbit last: the controls or auto-rotate
  // The second stage of a still view (devicePixels): done below the drawing buffer's pixels
  // (a phone's CSS size), it renders again at them, out of sight until done (issue #59).
  // It begins a second after the first stop, so a host that reads the converged image on
  // 'converged' (readPixels is asynchronous) still gets it.
  #device = { stage: false, done: false, startedAt: 0, pendingAt: 0 };
  #adapt; #renderSize = [0, 0]; #fullSize = [0, 0]; #needsPresent = true;
  #haveImage = false;          // a complete frame at the current render size exists
  #previewed = false;          // this view's first picture (the preview) was drawn
  #frameWorkMs = 0; #tiles = 0;  // time of the frame's parts so far; bands set in wasm
  #wasMoving = false; #refit = true;  // choose the still scale at the next still tick
  #envToken = 0;  // the last setEnvironment call (a stepped load stops when it is not)
  #loop; #running = false; #disposed = false; #lost = false; #dead = null;
  #resizeObserver = null;
  #sceneInfo = null; #report = ''; #context = '';
  #stats = { frame: 0, total: 0, converged: false, frameMs: 0, frame1Ms: 0, previewMs: 0,
             stepsPerTick: 0, partsPerTick: 0, split: 1, parts: 1, restartedAt: 0,
             convergedMs: 0, stage: 'css' };

  static async create(canvas, options = {}) {
    if (!canvas || typeof canvas.getContext !== 'function') {
      throw new PenumbraError('Penumbra.create needs a <canvas> element');
    }
    // An option given as undefined means "the default", as it would if left out.
    const given = Object.fromEntries(Object.entries(options).filter(([, v]) => v !== undefined));
    const opts = { ...DEFAULTS, ...given };
    let aborted = null;
    let mod;
    try {
      mod = await createPenumbraViewerModule({
        print: (t) => console.log(`[penumbra] ${t}`),
        printErr: (t) => console.warn(`[penumbra] ${t}`),
        onAbort: (what) => { aborted = String(what); if (viewer) viewer.#abort(aborted); },
      });
    } catch (e) {
      throw new PenumbraError(`cannot load the Penumbra module: ${e && e.message ? e.message : e}`);
    }
    if (!canvas.id) canvas.id = `penumbra-canvas-${++canvasIds}`;
    const selector = `#${CSS.escape(canvas.id)}`;
    // Emscripten looks canvases up with document.querySelector, which does not see into a shadow
    // root (<penumbra-viewer>): the module is given this one by its selector.
    mod.specialHTMLTargets[selector] = canvas;
    var viewer = new Viewer(mod, canvas, opts);
    if (aborted) throw new PenumbraError(`the Penumbra module aborted: ${aborted}`);
    const created = viewer.#call('pv_create', selector, opts.forceHalfFloat ? 1 : 0);
    viewer.#context = created.context;
    viewer.#report = created.report;
    viewer.#schema = [...viewer.#call('pv_settings_schema').settings.filter((e) => e.viewer),
                      ...JS_SCHEMA];
    viewer.#wasmKeys = new Set(viewer.#schema.map((e) => e.key).filter((k) => !JS_SETTINGS.has(k)));
    viewer.#attach();
    const initial = {};
    for (const [k, v] of Object.entries(given)) {
      if (viewer.#wasmKeys.has(k) || JS_SETTINGS.has(k)) initial[k] = v;
    }
    try {
      await viewer.setSettings(initial);
    } catch (e) {
      viewer.dispose();  // a bad option must not leave a context and listeners behind
      throw e;
    }
    viewer.#running = true;
    viewer.#loop.wake();
    return viewer;
  }

  constructor(mod, canvas, opts) {
    this.#mod = mod;
    this.#canvas = canvas;
    this.#opts = opts;
    this.#jsSettings = { budgetMs: opts.budgetMs, resolutionScale: opts.resolutionScale,
                         adaptiveResolution: opts.adaptiveResolution, maxSplit: opts.maxSplit,
                         devicePixels: opts.devicePixels };
    this.#adapt = new Adaptation({ minStillScale: opts.minStillScale,
                                   minMotionScale: opts.minMotionScale });
    this.#pv = bindWasmApi(mod);
    this.#loop = new FrameLoop(this.#step, (e) => this.#emitError(e));
  }

  // ---- public API ---------------------------------------------------------------------------

  get canvas() { return this.#canvas; }
  // The WebGL context description and the capability report (accumulation format etc.).
  get info() { return { context: this.#context, report: this.#report, scene: this.#sceneInfo }; }
  // A snapshot for progress displays and tests.
  get state() {
    const cost = this.#adapt.msPerPixel();
    return { ...this.#stats, lost: this.#lost, renderWidth: this.#renderSize[0],
             renderHeight: this.#renderSize[1], canvasWidth: this.#canvas.width,
             canvasHeight: this.#canvas.height, motionScale: this.#adapt.motionScale,
             stillScale: this.#adapt.currentStillScale(this.#jsSettings),
             pixelRatio: this.#pixelRatio(),
             msPerMegapixel: cost === null ? null : cost * 1e6,
             moving: this.#isMoving(performance.now()), paused: this.#loop.paused,
             looping: this.#loop.scheduled,
             gpuMemoryBytes: this.#lost || this.#dead ? 0 : this.#pv.pv_gpu_memory() };
  }
  // Every setting setSettings() takes: {key, type, min, max, default, range, help}, from the
  // renderer's schema plus the JS side's budgetMs and resolutionScale.
  get settingsSchema() {
    return this.#schema.map((e) => ({ ...e }));
  }

  // The camera in use: {eye, forward, up, yfov, znear, world (column-major camera-to-world),
  // orthographic, ymag, name}; the 'camera' event sends the same when it changes.
  get camera() {
    this.#check();
    return this.#call('pv_get_state').camera;
  }

  get settings() {
    const s = this.#lost ? { ...this.#overrides } : this.#call('pv_get_state').settings;
    for (const k of Object.keys(s)) if (!this.#wasmKeys.has(k)) delete s[k];
    // Values pass through float32 in wasm: show 0.3, not 0.30000001192092896.
    for (const [k, v] of Object.entries(s)) {
      if (typeof v === 'number' && !Number.isInteger(v)) s[k] = Number(v.toPrecision(7));
    }
    return { ...s, ...this.#jsSettings };
  }

  // Loads a scene file (.json), a .gltf or a .glb from a URL, bytes or a File. `resources`
  // maps file names to bytes for a .gltf's external files when they do not come from a URL.
  async loadScene(source, { name, resources } = {}) {
    this.#check();
    let main;
    if (typeof source === 'string' || source instanceof URL) {
      const url = new URL(String(source), location.href).href;
      main = { url, bytes: await fetchBytes(url), name: name || sourceName(url, 'scene') };
    } else {
      main = { bytes: await toBytes(source), name: name || sourceName(source, 'scene') };
    }
    const staged = await gatherScene(main, resources || {});
    await provideDecoders(this.#mod, staged.files);  // Draco/meshopt, only when the file needs them
    this.#check();
    const root = `/stage/${++stagingIds}`;
    // The automatic framing fits a model to the render size's aspect (RenderJob): the canvas's.
    this.#syncCanvasSize();
    const scale = this.#adapt.currentStillScale(this.#jsSettings);
    const size = this.#fullSize.map((n) => Math.max(1, Math.round(n * scale)));
    if (this.#fullSize[0] > 0 && (size[0] !== this.#renderSize[0] || size[1] !== this.#renderSize[1])) {
      this.#call('pv_set_settings', JSON.stringify({ width: size[0], height: size[1] }));
      this.#renderSize = size;
      this.#haveImage = false;
    }
    let info;
    try {
      for (const f of staged.files) this.#writeFile(`${root}/${f.path}`, f.bytes);
      const cut = staged.mainPath.lastIndexOf('/');
      info = this.#call('pv_load_scene', `${root}/${staged.mainPath.slice(0, cut)}`,
                        staged.mainPath.slice(cut + 1));
    } finally {
      this.#pv.pv_remove_tree(root);
    }
    this.#sceneInfo = { name: main.name, sceneFile: info.sceneFile,
                        triangles: info.triangles, lights: info.lights,
                        cameras: info.cameras, variants: info.variants, variant: info.variant,
                        warnings: info.warnings, bounds: info.bounds,
                        environment: info.environment };
    for (const w of info.warnings || []) {
      console.warn(`[penumbra] ${w.startsWith(main.name) ? w : `${main.name}: ${w}`}`);
    }
    // The user's own settings win over the scene file's.
    this.#call('pv_set_settings', JSON.stringify(this.#overrides));
    this.#orbit = OrbitCamera.fromCamera(info.camera, info.bounds);
    this.#cameraDirty = false;
    this.#adapt.reset();  // another scene costs differently: measure again
    this.#refit = true;
    this.#restarted();
    return this.#sceneInfo;
  }

  // KHR_materials_variants: shows the loaded scene's variant `name` (a name from
  // info.scene.variants, or its index; null or 'default' for the primitives' own materials).
  // Restarts the view; the geometry stays on the GPU.
  setVariant(name) {
    this.#check();
    const state = this.#call('pv_set_variant', name === null || name === undefined ? '' : String(name));
    if (this.#sceneInfo) this.#sceneInfo.variant = state.variant;
    this.#restarted();
    return state.variant;
  }

  // A packed environment (.hdr from penumbra-prefilter) or an equirectangular panorama
  // (.hdr/.png, prefiltered on load at a small size), from a URL, bytes or a File; [r, g, b]
  // for a uniform environment; 'studio' for the built-in neutral studio (as in a scene file);
  // null to forget the one set here and light by the rule (black with lights, else the studio).
  async setEnvironment(source, { name } = {}) {
    this.#check();
    const token = ++this.#envToken;  // a stepped load still running gives way to this one
    if (source === null || source === 'studio') {
      const state = this.#call('pv_set_builtin_environment', source === null ? 'default' : 'studio');
      if (this.#sceneInfo) this.#sceneInfo.environment = state.environment;
      this.#restarted();
      return;
    }
    if (Array.isArray(source)) {
      if (source.length !== 3 || !source.every(Number.isFinite)) {
        throw new PenumbraError('a uniform environment is [r, g, b]');
      }
      this.#call('pv_set_uniform_environment', ...source);
      this.#restarted();
      return;
    }
    let bytes;
    if (typeof source === 'string' || source instanceof URL) {
      bytes = await fetchBytes(new URL(String(source), location.href).href);
    } else {
      bytes = await toBytes(source);
    }
    this.#check();
    const shown = name || sourceName(source, 'environment.hdr');
    const tooLarge = panoramaTooLarge(bytes, shown);
    if (tooLarge) throw new PenumbraError(tooLarge);
    const file = shown.replace(/[^\w.+-]/g, '_');
    const size = radianceSize(bytes);
    let state;
    if (size && !size.packed && size.width * size.height > STEPPED_PANORAMA_PIXELS) {
      // A large panorama decodes in steps, the page running between them.
      this.#withHeapCopy(bytes, (ptr) => this.#call('pv_env_begin', ptr, bytes.length, file));
      const stale = () => token !== this.#envToken || !this.#usable();
      if (!await decodeInSteps((rows) => this.#call('pv_env_step', rows).done, stale)) return;
      state = this.#call('pv_env_finish');
    } else {
      const root = `/stage/${++stagingIds}`;
      try {
        this.#writeFile(`${root}/${file}`, bytes);
        state = this.#call('pv_set_environment', root, file);
      } finally {
        this.#pv.pv_remove_tree(root);
      }
    }
    if (this.#sceneInfo) this.#sceneInfo.environment = state.environment;
    this.#restarted();
  }

  // Auto-rotate: {enabled, speed (radians a second), delayMs} (autorotate.mjs; model-viewer's
  // defaults). The view turns once left alone for delayMs; an interaction restarts the delay.
  setAutoRotate(options) {
    this.#check();
    try {
      this.#autoRotate.configure(options, performance.now());
    } catch (e) {
      throw new PenumbraError(e.message);
    }
    this.#loop.wake();
  }

  // {eye, target, up?, yfov?} in scene units (yfov in radians), or 'reset' for the scene's own.
  async setCamera(camera) {
    this.#check();
    if (camera === 'reset') {
      const cam = this.#call('pv_reset_camera');
      if (this.#sceneInfo) this.#orbit = OrbitCamera.fromCamera(cam, this.#sceneInfo.bounds);
      this.#restarted();
      this.#emit('camera', { ...cam, source: 'none' });
      return;
    }
    const v3 = (v, what) => {
      if (!Array.isArray(v) || v.length !== 3 || !v.every(Number.isFinite)) {
        throw new PenumbraError(`camera: '${what}' must be [x, y, z]`);
      }
      return v;
    };
    const eye = v3(camera && camera.eye, 'eye'), target = v3(camera.target, 'target');
    const up = camera.up ? v3(camera.up, 'up') : [0, 1, 0];
    const yfov = camera.yfov ?? (this.#orbit ? this.#orbit.yfov : 0.8);
    const cam = this.#call('pv_set_camera', ...eye, ...target, ...up, yfov);
    if (!this.#orbit) this.#orbit = new OrbitCamera();
    this.#orbit.target = [...target];
    this.#orbit.yfov = yfov;
    this.#orbit.setEye(eye);
    this.#restarted();
    this.#emit('camera', { ...cam, source: 'none' });
  }

  // Any key of settingsSchema (frames, fd, occlusionDistance, exposure, toneMapper,
  // screenSpaceIndirect, indirectClamp, ..., budgetMs, resolutionScale). Resolves to the full
  // settings.
  async setSettings(changes = {}) {
    this.#check();
    const wasm = {};
    const js = {};
    for (const [k, v] of Object.entries(changes)) {
      if (v === undefined) continue;
      if (this.#wasmKeys.has(k)) wasm[k] = v;
      else if (JS_SETTINGS.has(k)) js[k] = v;
      else throw new PenumbraError(`unknown setting '${k}'`);
    }
    for (const [k, v] of Object.entries(js)) {
      const bad = checkJsSetting(k, v);
      if (bad) throw new PenumbraError(bad);
    }
    if (!this.#lost && Object.keys(wasm).length) this.#call('pv_set_settings', JSON.stringify(wasm));
    Object.assign(this.#overrides, wasm);
    Object.assign(this.#jsSettings, js);
    // A change while sharpening shows at once: back to the still view's own size.
    if (this.#device.stage && !this.#device.done) this.#device.stage = false;
    if (this.#device.pendingAt) this.#device.pendingAt = performance.now() + DEVICE_STAGE_DELAY_MS;
    if (Object.keys(js).length) this.#refit = true;  // budget or bounds changed: choose again
    this.#needsPresent = true;  // exposure and tone mapping change the display without a restart
    this.#loop.wake();
    return this.#lost ? { ...this.#overrides, ...this.#jsSettings } : this.settings;
  }

  // Stops drawing (an off-screen or hidden view) until resume(); what accumulated stays, and
  // changes made meanwhile apply on resume.
  pause() { this.#loop.pause(); }
  resume() { this.#loop.resume(); }

  // Restarts accumulation at frame 1.
  restart() {
    if (this.#usable()) { this.#pv.pv_restart(); this.#restarted(); }
  }

  on(event, handler) {
    if (!this.#listeners.has(event)) this.#listeners.set(event, new Set());
    this.#listeners.get(event).add(handler);
    return () => this.off(event, handler);
  }
  off(event, handler) { this.#listeners.get(event)?.delete(handler); }

  // The canvas as a PNG Blob (the context keeps its drawing buffer, so this is what is shown).
  screenshot() {
    return new Promise((resolve, reject) => {
      this.#canvas.toBlob((b) => (b ? resolve(b) : reject(new PenumbraError('screenshot failed'))),
                          'image/png');
    });
  }

  // The last complete frame at the render size as {width, height, frames, data, canvasWidth,
  // canvasHeight}: RGBA floats, row 0 at the top; the linear radiance before exposure, or with
  // {display: true} the image as displayed (exposure, tone mapping, sRGB; in [0, 1]). The render
  // size is the canvas's drawing-buffer size at rest on a desktop, and may be lower on a
  // high-DPR phone (never below the CSS size) or while moving: canvasWidth/Height say which.
  async readPixels({ display = false } = {}) {
    this.#check();
    const r = this.#call('pv_read', display ? 1 : 0);
    const data = new Float32Array(this.#mod.HEAPU8.buffer, r.ptr, r.width * r.height * 4).slice();
    return { width: r.width, height: r.height, frames: r.frames, data,
             canvasWidth: this.#fullSize[0], canvasHeight: this.#fullSize[1] };
  }

  // Milliseconds per intermediate frame at the current size: one warm-up accumulation (shaders
  // compile on first use), then `frames` steps back to back with one read-back at the end
  // (throughput, as penumbra-render measures it), and the same with a read-back after every
  // step (latency, what the time budget sees). The frame loop pauses meanwhile.
  async benchmark({ frames } = {}) {
    this.#check();
    const wasRunning = this.#running;
    this.#running = false;
    try {
      const m = frames || this.#pv.pv_total_frames();
      const run = (syncEach) => {
        const r = timeSteps(this.#pv, m, syncEach);
        if (r.frames === 0) throw new PenumbraError(this.#lastError());
        return r;
      };
      run(false);  // warm-up
      const a = run(false);
      const b = run(true);
      this.#restarted();
      return { frames: a.frames, width: this.#renderSize[0], height: this.#renderSize[1],
               msPerFrame: a.ms / a.frames, msPerFrameSynced: b.ms / b.frames, totalMs: a.ms };
    } finally {
      this.#running = wasRunning;
    }
  }

  dispose() {
    if (this.#disposed) return;
    this.#disposed = true;
    this.#running = false;
    this.#loop.stop();
    this.#resizeObserver?.disconnect();
    window.removeEventListener('resize', this.#loop.wake);
    this.#controls?.detach();
    this.#canvas.removeEventListener('webglcontextlost', this.#onLost);
    this.#canvas.removeEventListener('webglcontextrestored', this.#onRestored);
    try { this.#pv.pv_destroy(); } catch { /* an aborted module has nothing left to free */ }
    this.#listeners.clear();
  }

  // ---- internals ----------------------------------------------------------------------------

  #attach() {
    this.#canvas.addEventListener('webglcontextlost', this.#onLost);
    this.#canvas.addEventListener('webglcontextrestored', this.#onRestored);
    // The loop sleeps once converged (#step): a new CSS size or pixel ratio wakes it.
    if (this.#opts.autoResize && typeof ResizeObserver === 'function') {
      this.#resizeObserver = new ResizeObserver(this.#loop.wake);
      this.#resizeObserver.observe(this.#canvas);
    }
    window.addEventListener('resize', this.#loop.wake);
    if (this.#opts.controls) {
      this.#controls = attachOrbitControls(this.#canvas, {
        // Proxy so the controls always act on the current scene's orbit camera.
        orbit: (...a) => this.#orbit?.orbit(...a), pan: (...a) => this.#orbit?.pan(...a),
        zoom: (...a) => this.#orbit?.zoom(...a),
      }, {
        onChange: () => {
          if (!this.#orbit) return;
          this.#cameraSource = 'user-interaction';
          this.#cameraDirty = true;
          this.#lastChange = performance.now();
          this.#autoRotate.interacted(this.#lastChange);
          this.#loop.wake();
        },
        onReset: () => { if (this.#sceneInfo) this.setCamera('reset').catch((e) => this.#emitError(e)); },
      });
    }
  }

  #onLost = (e) => {
    e.preventDefault();  // without this the browser never restores the context
    this.#lost = true;
    try { this.#pv.pv_context_lost(); } catch (err) { this.#emitError(err); }
    this.#emit('contextlost', {});
  };

  #onRestored = () => {
    if (this.#disposed || this.#dead) return;
    try {
      const r = this.#call('pv_context_restored');
      this.#context = r.context;
      this.#report = r.report;
      this.#lost = false;
      this.#call('pv_set_settings', JSON.stringify(this.#overrides));
      this.#renderSize = [0, 0];  // the new renderer starts at its default size
      this.#tiles = 0;            // and with whole frames
      this.#haveImage = false;
      this.#adapt.reset();
      this.#refit = true;
      this.#restarted();
      this.#emit('contextrestored', {});
    } catch (err) {
      this.#emitError(err);
    }
  };

  #call(name, ...args) {
    if (this.#dead) throw new PenumbraError(`the Penumbra module aborted: ${this.#dead}`);
    let text;
    try {
      text = this.#pv[name](...args);
    } catch (e) {
      throw new PenumbraError(`${name}: ${e && e.message ? e.message : e}`);
    }
    const result = JSON.parse(text);
    if (result && typeof result === 'object' && typeof result.error === 'string') {
      throw new PenumbraError(result.error);
    }
    return result;
  }

  #writeFile(path, bytes) {
    this.#withHeapCopy(bytes, (ptr) => this.#call('pv_write_file', path, ptr, bytes.length), path);
  }

  // Calls fn(ptr) with `bytes` copied into the wasm heap at ptr (freed after).
  #withHeapCopy(bytes, fn, what = 'a file') {
    const ptr = this.#pv.pv_alloc(bytes.length);
    if (!ptr && bytes.length) throw new PenumbraError(`out of memory staging ${what}`);
    try {
      this.#mod.HEAPU8.set(bytes, ptr);
      return fn(ptr);
    } finally {
      this.#pv.pv_free(ptr);
    }
  }

  #lastError() { return this.#call('pv_last_error') || 'step failed'; }
  #usable() { return !this.#disposed && !this.#dead && !this.#lost; }
  #check() {
    if (this.#disposed) throw new PenumbraError('the viewer has been disposed');
    if (this.#dead) throw new PenumbraError(`the Penumbra module aborted: ${this.#dead}`);
    if (this.#lost) throw new PenumbraError('the WebGL context is lost (waiting for restore)');
  }
  #abort(what) {
    this.#dead = what;
    this.#running = false;
    this.#emitError(new PenumbraError(`the Penumbra module aborted: ${what}`));
  }

  #emit(event, detail) {
    for (const fn of this.#listeners.get(event) || []) {
      try { fn(detail); } catch (e) { console.error(e); }  // a handler must not stop the loop
    }
  }
  #emitError(e) {
    const err = e instanceof Error ? e : new PenumbraError(String(e));
    if (!this.#listeners.get('error')?.size) console.error(err);
    this.#emit('error', err);
  }

  #restarted(keepStage = false) {
    if (!keepStage) Object.assign(this.#device, { stage: false, done: false, pendingAt: 0 });
    this.#stats.stage = this.#device.stage ? (this.#device.done ? 'device' : 'sharpening') : 'css';
    this.#previewed = false;
    this.#frameWorkMs = 0;  // wasm drops a frame in progress on any restart
    this.#loop.wake();
    if (keepStage) return;  // sharpening: the view stays converged (and its time) as shown
    this.#stats.restartedAt = performance.now();
    this.#stats.converged = false;
  }

  // Moving = the camera changed within stillMs. A finger or button held still does not count:
  // the full-resolution image should come back as soon as the view stops changing.
  #isMoving(now) {
    return now - this.#lastChange < this.#opts.stillMs;
  }

  // The drawing buffer's size at rest: CSS size x pixel ratio (autoResize), else the host's.
  #syncCanvasSize() {
    const c = this.#canvas;
    let size = [c.width, c.height];
    if (this.#opts.autoResize && c.clientWidth && c.clientHeight) {
      const ratio = this.#pixelRatio();
      size = [Math.max(1, Math.round(c.clientWidth * ratio)),
              Math.max(1, Math.round(c.clientHeight * ratio))];
    }
    if (size[0] !== this.#fullSize[0] || size[1] !== this.#fullSize[1]) {
      this.#fullSize = size;
      this.#refit = true;  // another pixel count: choose the still scale again
    }
  }

  // Tone-maps the accumulation into the canvas. A moving preview gets a drawing buffer of its
  // own size, scaled up by the browser (a phone's full buffer costs more to fill and composite
  // than the preview's frame); resized only here, with an image to draw (a resize clears it).
  #present(preview) {
    const c = this.#canvas;
    const [w, h] = preview && this.#opts.autoResize ? this.#renderSize : this.#fullSize;
    if (this.#opts.autoResize && (c.width !== w || c.height !== h)) {
      c.width = w;
      c.height = h;
    }
    this.#call('pv_present', c.width, c.height);
    this.#needsPresent = false;
  }

  #pixelRatio() {
    return effectivePixelRatio(this.#opts, globalThis.devicePixelRatio);
  }

  // One animation frame of the loop (loop.mjs). Returns false once converged with nothing new
  // to show: the loop then sleeps until a change wakes it (#restarted, setSettings, the
  // controls, a resize, resume()); also while lost, dead or benchmarking, which wake it after.
  #step = () => {
    if (this.#disposed || !this.#running || this.#dead || this.#lost) return false;
    this.#frame();
    // Auto-rotate keeps the loop awake while it waits for its delay and while it turns.
    return !(this.#stats.converged && !this.#needsPresent && !this.#cameraDirty &&
             !this.#isMoving(performance.now()) && !this.#autoRotate.enabled &&
             !(this.#device.stage && !this.#device.done) && !this.#device.pendingAt);
  };

  #frame() {
    this.#syncCanvasSize();
    const now = performance.now();
    if (this.#sceneInfo && this.#autoRotate.advance(this.#orbit, now)) {
      this.#cameraSource = 'automatic';
      this.#cameraDirty = true;
      this.#lastChange = now;  // a turning view is a moving one
    }
    const moving = this.#isMoving(now);
    const js = this.#jsSettings;
    const canvasPixels = this.#fullSize[0] * this.#fullSize[1];
    // The still image's floor: the canvas's CSS size (its layout size where the page shows it).
    const css = this.#canvas.clientWidth;
    this.#adapt.cssScale = css > 0 ? Math.min(1, css / this.#fullSize[0]) : 1 / this.#pixelRatio();
    if (moving) {
      if (!this.#wasMoving) this.#adapt.startMotion(js, canvasPixels);
      this.#wasMoving = true;
    } else if (this.#wasMoving || this.#refit) {
      // At rest (again): choose the still resolution from what frames cost here.
      this.#wasMoving = false;
      this.#refit = false;
      this.#adapt.refit(js, canvasPixels);
    }
    if (moving) Object.assign(this.#device, { stage: false, pendingAt: 0 });
    if (this.#device.pendingAt && now >= this.#device.pendingAt) {
      Object.assign(this.#device, { stage: true, done: false, startedAt: now, pendingAt: 0 });
      this.#stats.stage = 'sharpening';
    }
    const stillScale = this.#adapt.currentStillScale(js);
    const scale = moving ? Math.min(stillScale, this.#adapt.motionScale)
      : this.#device.stage ? js.resolutionScale : stillScale;
    const preview = scale < stillScale;  // a moving preview, not the image to converge
    const w = Math.max(1, Math.round(this.#fullSize[0] * scale));
    const h = Math.max(1, Math.round(this.#fullSize[1] * scale));
    if (w !== this.#renderSize[0] || h !== this.#renderSize[1]) {
      this.#call('pv_set_settings', JSON.stringify({ width: w, height: h }));
      this.#renderSize = [w, h];
      this.#haveImage = false;  // new targets: nothing to show until a frame completes
      this.#restarted(this.#device.stage);
    }
    if (this.#cameraDirty && this.#orbit) {
      const c = this.#orbit.toCamera();
      const cam = this.#call('pv_set_camera', ...c.eye, ...c.target, ...c.up, c.yfov);
      this.#cameraDirty = false;
      this.#restarted();
      this.#emit('camera', { ...cam, source: this.#cameraSource });
    }
    if (!this.#sceneInfo) return;  // nothing to show yet
    // A view's first picture: frame 1 at the preview's size (a quarter of the pixels), shown at
    // once and left out of the mean; the full frame 1 follows in the next animation frames.
    // On a slow device it comes several times sooner than a whole frame 1 would.
    const sharpening = this.#device.stage && !this.#device.done;  // the canvas keeps stage 1
    if (!this.#haveImage && !this.#previewed && !moving && !sharpening &&
        this.#pv.pv_frames_done() === 0) {
      this.#previewed = true;
      const start = performance.now();
      this.#call('pv_preview');
      this.#pv.pv_sync();
      this.#stats.previewMs = performance.now() - start;
      this.#haveImage = true;
      this.#present(false);
      return;
    }

    let parts = 0, frames = 0;
    if (!this.#pv.pv_converged()) {
      const start = performance.now();
      let prev = start;
      for (;;) {
        this.#setTiles(moving);  // wasm applies it when a frame begins
        const r = this.#pv.pv_step_part();
        if (r < 0) throw new PenumbraError(this.#lastError());
        if (r === 0) break;
        this.#pv.pv_sync();
        const t = performance.now();
        const dt = t - prev;
        prev = t;
        parts++;
        if (this.#pv.pv_last_part() === 1) this.#frameWorkMs = 0;  // a frame began
        this.#frameWorkMs += dt;
        if (r === 1) {
          frames++;
          // The still scale went down: the next tick restarts at the new size.
          if (this.#frameCompleted(moving, canvasPixels)) break;
        }
        // Stop when the next part, if it costs what this one did, would overrun the budget.
        if (this.#pv.pv_converged() || (t - start) + dt > js.budgetMs) break;
      }
      this.#stats.partsPerTick = parts;
    }
    // Only complete frames are shown: a frame in progress leaves the previous mean in place.
    if ((frames > 0 || this.#needsPresent) && this.#haveImage && !sharpening) this.#present(preview);
    if (frames === 0) return;
    const frame = this.#pv.pv_frames_done(), total = this.#pv.pv_total_frames();
    if (sharpening) {
      if (!this.#pv.pv_converged()) return;
      // Done at device pixels: shown now; 'converged' keeps its meaning (the first stop).
      Object.assign(this.#device, { done: true });
      Object.assign(this.#stats, { frame, total, converged: true, stage: 'device' });
      this.#present(false);
      const [width, height] = this.#renderSize;
      this.#emit('sharpened', { frame, total, width, height,
                                milliseconds: performance.now() - this.#device.startedAt });
      return;
    }
    Object.assign(this.#stats, { frame, total, stepsPerTick: frames });
    this.#emit('progress', { frame, total });
    // A moving preview is not the result: no 'converged' for it.
    if (this.#pv.pv_converged() && !this.#stats.converged && !preview) {
      this.#stats.converged = true;
      this.#stats.convergedMs = performance.now() - this.#stats.restartedAt;
      this.#emit('converged', { frame, total, milliseconds: this.#stats.convergedMs });
      const [w0, h0] = this.#renderSize;
      const full = [Math.round(this.#fullSize[0] * js.resolutionScale),
                    Math.round(this.#fullSize[1] * js.resolutionScale)];
      if (js.devicePixels && (w0 < full[0] || h0 < full[1])) {
        this.#device.pendingAt = performance.now() + DEVICE_STAGE_DELAY_MS;
      }
    }
  }

  // Bands for the next frame to begin (adapt.mjs: predicted cost / budget, at most maxSplit;
  // frame 1 whole while moving). Set in wasm only when it changes.
  #setTiles(moving) {
    const [w, h] = this.#renderSize;
    const k = this.#adapt.tiles(this.#jsSettings, w * h,
                                { moving, frameOne: this.#pv.pv_frames_done() === 0 });
    if (k !== this.#tiles) this.#tiles = this.#pv.pv_set_tiles(k);
    this.#stats.split = this.#tiles;
  }

  // A frame completed: record its cost, learn from it. True when the still scale went down.
  #frameCompleted(moving, canvasPixels) {
    const ms = this.#frameWorkMs;
    this.#frameWorkMs = 0;
    this.#haveImage = true;
    // Sharpening's frames do not move the still scale: their size is the buffer's on purpose.
    if (this.#device.stage) return false;
    const frame = this.#pv.pv_frames_done();
    const [w, h] = this.#renderSize;
    this.#stats.frameMs = ms;
    this.#stats.parts = this.#pv.pv_last_parts();
    if (frame === 1) this.#stats.frame1Ms = ms;
    return this.#adapt.frameDone(this.#jsSettings,
                                 { frame, ms, renderPixels: w * h, canvasPixels, moving });
  }
}

export const Penumbra = { create: (canvas, options) => Viewer.create(canvas, options), version };
export default Penumbra;
