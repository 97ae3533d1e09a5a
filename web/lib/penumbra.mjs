// Penumbra's JavaScript API: a progressive physically-based viewer on a <canvas>.
//
//   import Penumbra from './lib/penumbra.mjs';
//   const viewer = await Penumbra.create(canvas, { budgetMs: 12 });
//   await viewer.loadScene('assets/cornell_box/cornell_box.json');
//   viewer.on('progress', ({ frame, total }) => ...);
//
// The wasm module (the native renderer's C++ and GLSL) draws cheap intermediate frames and
// accumulates them. This file owns the frame loop: each requestAnimationFrame draws as many
// frames, or parts of one, as fit the time budget (timed by a 1-pixel read-back), then
// tone-maps into the canvas. A camera change or a played pose restarts at frame 1; adapt.mjs
// chooses the resolution (lower while moving) and the split from measured costs. Methods that
// can fail reject with a PenumbraError (the one-line C++ message); the frame loop and handlers
// never throw ('error' event). docs/web/api.md documents the API.
import { ADAPT_DEFAULTS, Adaptation, JS_SCHEMA, effectivePixelRatio, splitSettings } from './adapt.mjs';
import { provideDecoders } from './decoders.mjs';
import { Emitter, WasmSession } from './session.mjs';
import { OrbitCamera, attachOrbitControls, cameraFromOptions } from './orbit.mjs';
import { FrameLoop, drawParts } from './loop.mjs';
import { AnimationPlayer } from './animation.mjs';
import { AutoRotate } from './autorotate.mjs';
import { DownloadProgress, PenumbraError, fetchBytes, gatherScene, sourceName, toBytes }
  from './staging.mjs';
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
// The renderer's settings come from the wasm module's schema (penumbra/settings.h); JS_SCHEMA
// (adapt.mjs) holds the JS side's own.
const JS_SETTINGS = new Set(JS_SCHEMA.map((e) => e.key));
const DEVICE_STAGE_DELAY_MS = 1000;  // the device-pixel stage begins this long after the stop

export class Viewer {
  #s; #pv; #canvas; #opts; #events = new Emitter();  // session.mjs
  #schema = []; #wasmKeys = new Set();  // the settings schema; keys setSettings() sends to wasm
  #overrides = {};             // wasm settings the user set (re-applied after loads/restores)
  #jsSettings;                 // budgetMs, resolutionScale, adaptiveResolution, maxSplit
  #orbit = null; #controls = null; #cameraDirty = false; #lastChange = -Infinity;
  #autoRotate = new AutoRotate();  // autorotate.mjs: turns the orbit once left alone
  #player = new AnimationPlayer(() => this.#loop?.wake());  // animation.mjs: the model's clips
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
  #envToken = 0;  // the last setEnvironment call (a stepped load stops when it is not)
  #loop; #running = false; #disposed = false; #lost = false;
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
    const { session, selector } = await WasmSession.load(canvas);
    const viewer = new Viewer(session, canvas, opts);
    session.onAbort = (what) => viewer.#abort(what);
    const created = viewer.#s.call('pv_create', selector, opts.forceHalfFloat ? 1 : 0);
    viewer.#context = created.context;
    viewer.#report = created.report;
    viewer.#schema = [...viewer.#s.call('pv_settings_schema').settings.filter((e) => e.viewer),
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

  constructor(session, canvas, opts) {
    this.#s = session;
    this.#pv = session.pv;
    this.#canvas = canvas;
    this.#opts = opts;
    this.#jsSettings = { budgetMs: opts.budgetMs, resolutionScale: opts.resolutionScale,
                         adaptiveResolution: opts.adaptiveResolution, maxSplit: opts.maxSplit,
                         devicePixels: opts.devicePixels };
    this.#adapt = new Adaptation({ minStillScale: opts.minStillScale,
                                   minMotionScale: opts.minMotionScale });
    this.#loop = new FrameLoop(this.#step, (e) => this.#events.emitError(e));
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
             gpuMemoryBytes: this.#lost || this.#s.dead ? 0 : this.#pv.pv_gpu_memory() };
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
    return this.#s.call('pv_get_state').camera;
  }

  get settings() {
    const s = this.#lost ? { ...this.#overrides } : this.#s.call('pv_get_state').settings;
    for (const k of Object.keys(s)) if (!this.#wasmKeys.has(k)) delete s[k];
    // Values pass through float32 in wasm: show 0.3, not 0.30000001192092896.
    for (const [k, v] of Object.entries(s)) {
      if (typeof v === 'number' && !Number.isInteger(v)) s[k] = Number(v.toPrecision(7));
    }
    return { ...s, ...this.#jsSettings };
  }

  // Loads a scene file (.json), a .gltf or a .glb from a URL, bytes or a File. `resources`
  // maps file names to bytes for a .gltf's external files when they do not come from a URL.
  // onProgress(p) follows the download (DownloadProgress: 0 to under 1, never going back).
  async loadScene(source, { name, resources, onProgress } = {}) {
    this.#check();
    const progress = onProgress ? new DownloadProgress(onProgress) : null;
    let main;
    if (typeof source === 'string' || source instanceof URL) {
      const url = new URL(String(source), location.href).href;
      const bytes = await fetchBytes(url, progress?.file(url));
      main = { url, bytes, name: name || sourceName(url, 'scene') };
    } else {
      main = { bytes: await toBytes(source), name: name || sourceName(source, 'scene') };
    }
    const staged = await gatherScene(main, resources || {}, progress);
    await provideDecoders(this.#s.mod, staged.files);  // Draco/meshopt, only when the file needs them
    this.#check();
    // The automatic framing fits a model to the render size's aspect (RenderJob): the canvas's.
    this.#syncCanvasSize();
    const scale = this.#adapt.currentStillScale(this.#jsSettings);
    const size = this.#fullSize.map((n) => Math.max(1, Math.round(n * scale)));
    if (this.#fullSize[0] > 0 && (size[0] !== this.#renderSize[0] || size[1] !== this.#renderSize[1])) {
      this.#s.call('pv_set_settings', JSON.stringify({ width: size[0], height: size[1] }));
      this.#renderSize = size;
      this.#haveImage = false;
    }
    const cut = staged.mainPath.lastIndexOf('/');
    const info = this.#s.staged(staged.files, (root) => this.#s.call(
      'pv_load_scene', `${root}/${staged.mainPath.slice(0, cut)}`, staged.mainPath.slice(cut + 1)));
    this.#sceneInfo = { name: main.name, sceneFile: info.sceneFile,
                        triangles: info.triangles, lights: info.lights,
                        cameras: info.cameras, variants: info.variants, variant: info.variant,
                        warnings: info.warnings, bounds: info.bounds, animations: info.animations,
                        environment: info.environment };
    for (const w of info.warnings || []) {
      console.warn(`[penumbra] ${w.startsWith(main.name) ? w : `${main.name}: ${w}`}`);
    }
    // The user's own settings win over the scene file's.
    this.#s.call('pv_set_settings', JSON.stringify(this.#overrides));
    this.#orbit = OrbitCamera.fromCamera(info.camera, info.bounds);
    this.#cameraDirty = false;
    this.#player.reset(info.animations);
    this.#adapt.reset();  // another scene costs differently: measure again
    this.#restarted();
    return this.#sceneInfo;
  }

  // KHR_materials_variants: shows variant `name` (of info.scene.variants, or its index; null or
  // 'default': the primitives' own materials). Restarts the view; the geometry stays.
  setVariant(name) {
    this.#check();
    const state = this.#s.call('pv_set_variant', name === null || name === undefined ? '' : String(name));
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
    const state = await this.#s.setEnvironment(source, name, {
      check: () => this.#check(), stale: () => token !== this.#envToken || !this.#usable() });
    if (!state) return;  // another environment was set meanwhile
    if (this.#sceneInfo && state.environment) this.#sceneInfo.environment = state.environment;
    this.#restarted();
  }

  // model-viewer's skybox-image: the background from another environment file (as
  // setEnvironment takes), lighting nothing; null shows the environment again.
  async setSkybox(source, { name } = {}) {
    this.#check();
    await this.#s.setSkybox(source ?? null, name, () => this.#check());
    this.#restarted();
  }

  // The loaded model's animations (animation.mjs): .animations, .select(name), .play(),
  // .pause(), .seek(seconds), .time, .playing, .duration; posed on the GPU each frame it plays.
  get animation() { return this.#player; }

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
      const cam = this.#s.call('pv_reset_camera');
      if (this.#sceneInfo) this.#orbit = OrbitCamera.fromCamera(cam, this.#sceneInfo.bounds);
      this.#restarted();
      this.#events.emit('camera', { ...cam, source: 'none' });
      return;
    }
    const { eye, target, up, yfov, error } = cameraFromOptions(camera, this.#orbit?.yfov ?? 0.8);
    if (error) throw new PenumbraError(error);
    const cam = this.#s.call('pv_set_camera', ...eye, ...target, ...up, yfov);
    if (!this.#orbit) this.#orbit = new OrbitCamera();
    this.#orbit.target = [...target];
    this.#orbit.yfov = yfov;
    this.#orbit.setEye(eye);
    this.#restarted();
    this.#events.emit('camera', { ...cam, source: 'none' });
  }

  // Any key of settingsSchema (frames, fd, occlusionDistance, exposure, toneMapper,
  // screenSpaceIndirect, indirectClamp, ..., budgetMs, resolutionScale). Resolves to the full
  // settings.
  async setSettings(changes = {}) {
    this.#check();
    const { wasm, js, error } = splitSettings(changes, this.#wasmKeys);
    if (error) throw new PenumbraError(error);
    if (!this.#lost && Object.keys(wasm).length) this.#s.call('pv_set_settings', JSON.stringify(wasm));
    Object.assign(this.#overrides, wasm);
    Object.assign(this.#jsSettings, js);
    // A change while sharpening shows at once: back to the still view's own size.
    if (this.#device.stage && !this.#device.done) this.#device.stage = false;
    if (this.#device.pendingAt) this.#device.pendingAt = performance.now() + DEVICE_STAGE_DELAY_MS;
    if (Object.keys(js).length) this.#adapt.refitLater();  // budget or bounds changed
    this.#needsPresent = true;  // exposure and tone mapping change the display without a restart
    this.#loop.wake();
    return this.#lost ? { ...this.#overrides, ...this.#jsSettings } : this.settings;
  }

  // Stops drawing (an off-screen or hidden view) until resume(); what accumulated stays, and
  // changes made meanwhile apply on resume. restart(): accumulation from frame 1.
  pause() { this.#loop.pause(); }
  resume() { this.#loop.resume(); }
  restart() { if (this.#usable()) { this.#pv.pv_restart(); this.#restarted(); } }
  on(event, handler) { return this.#events.on(event, handler); }
  off(event, handler) { this.#events.off(event, handler); }

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
    const [canvasWidth, canvasHeight] = this.#fullSize;
    return { ...this.#s.read(display), canvasWidth, canvasHeight };
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
      const r = this.#s.benchmark(frames || this.#pv.pv_total_frames());
      this.#restarted();
      return { ...r, width: this.#renderSize[0], height: this.#renderSize[1] };
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
    this.#events.clear();
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
      // The controls always act on the current scene's orbit camera.
      this.#controls = attachOrbitControls(this.#canvas, () => this.#orbit, {
        onChange: () => {
          if (!this.#orbit) return;
          this.#cameraSource = 'user-interaction';
          this.#cameraDirty = true;
          this.#lastChange = performance.now();
          this.#autoRotate.interacted(this.#lastChange);
          this.#loop.wake();
        },
        onReset: () => { if (this.#sceneInfo) this.setCamera('reset').catch((e) => this.#events.emitError(e)); },
      });
    }
  }

  #onLost = (e) => {
    e.preventDefault();  // without this the browser never restores the context
    this.#lost = true;
    try { this.#pv.pv_context_lost(); } catch (err) { this.#events.emitError(err); }
    this.#events.emit('contextlost', {});
  };

  #onRestored = () => {
    if (this.#disposed || this.#s.dead) return;
    try {
      const r = this.#s.call('pv_context_restored');
      this.#context = r.context;
      this.#report = r.report;
      this.#lost = false;
      this.#s.call('pv_set_settings', JSON.stringify(this.#overrides));
      this.#renderSize = [0, 0];  // the new renderer starts at its default size
      this.#tiles = 0;            // and with whole frames
      this.#haveImage = false;
      this.#adapt.reset();
      this.#restarted();
      this.#events.emit('contextrestored', {});
    } catch (err) {
      this.#events.emitError(err);
    }
  };

  #usable() { return !this.#disposed && !this.#s.dead && !this.#lost; }
  #check() {
    if (this.#disposed) throw new PenumbraError('the viewer has been disposed');
    if (this.#s.dead) throw new PenumbraError(`the Penumbra module aborted: ${this.#s.dead}`);
    if (this.#lost) throw new PenumbraError('the WebGL context is lost (waiting for restore)');
  }
  #abort(what) {
    this.#running = false;
    this.#events.emitError(new PenumbraError(`the Penumbra module aborted: ${what}`));
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
  #isMoving(now) { return now - this.#lastChange < this.#opts.stillMs; }

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
      this.#adapt.refitLater();  // another pixel count: choose the still scale again
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
    this.#s.call('pv_present', c.width, c.height);
    this.#needsPresent = false;
  }

  #pixelRatio() { return effectivePixelRatio(this.#opts, globalThis.devicePixelRatio); }

  // One animation frame of the loop (loop.mjs). Returns false once converged with nothing new
  // to show: the loop then sleeps until a change wakes it (#restarted, setSettings, the
  // controls, a resize, resume()); also while lost, dead or benchmarking, which wake it after.
  #step = () => {
    if (this.#disposed || !this.#running || this.#s.dead || this.#lost) return false;
    this.#frame();
    // Auto-rotate keeps the loop awake while it waits for its delay and while it turns.
    return !(this.#stats.converged && !this.#needsPresent && !this.#cameraDirty &&
             !this.#isMoving(performance.now()) && !this.#autoRotate.enabled && !this.#player.playing &&
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
    const pose = this.#sceneInfo && this.#player.advance(now);
    if (pose) {
      this.#s.call('pv_set_pose', ...pose);
      if (this.#player.playing) this.#lastChange = now;  // a playing animation is a moving view
      this.#restarted();
    }
    const moving = this.#isMoving(now);
    const js = this.#jsSettings;
    const canvasPixels = this.#fullSize[0] * this.#fullSize[1];
    // The still image's floor: the canvas's CSS size (its layout size where the page shows it).
    const css = this.#canvas.clientWidth;
    this.#adapt.cssScale = css > 0 ? Math.min(1, css / this.#fullSize[0]) : 1 / this.#pixelRatio();
    this.#adapt.update(js, canvasPixels, moving);
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
      this.#s.call('pv_set_settings', JSON.stringify({ width: w, height: h }));
      this.#renderSize = [w, h];
      this.#haveImage = false;  // new targets: nothing to show until a frame completes
      this.#restarted(this.#device.stage);
    }
    if (this.#cameraDirty && this.#orbit) {
      const c = this.#orbit.toCamera();
      const cam = this.#s.call('pv_set_camera', ...c.eye, ...c.target, ...c.up, c.yfov);
      this.#cameraDirty = false;
      this.#restarted();
      this.#events.emit('camera', { ...cam, source: this.#cameraSource });
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
      this.#s.call('pv_preview');
      this.#pv.pv_sync();
      this.#stats.previewMs = performance.now() - start;
      this.#haveImage = true;
      this.#present(false);
      return;
    }

    let frames = 0;
    if (!this.#pv.pv_converged()) {
      const drawn = drawParts(this.#pv, js.budgetMs, {
        beforePart: () => this.#setTiles(moving),  // wasm applies it when a frame begins
        onPart: (ms, began) => { this.#frameWorkMs = (began ? 0 : this.#frameWorkMs) + ms; },
        // True when the still scale went down: the next tick restarts at the new size.
        onFrame: () => this.#frameCompleted(moving, canvasPixels),
        error: () => new PenumbraError(this.#s.lastError()) });
      frames = drawn.frames;
      this.#stats.partsPerTick = drawn.parts;
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
      this.#events.emit('sharpened', { frame, total, width, height,
                                milliseconds: performance.now() - this.#device.startedAt });
      return;
    }
    Object.assign(this.#stats, { frame, total, stepsPerTick: frames });
    this.#events.emit('progress', { frame, total });
    // A moving preview is not the result: no 'converged' for it.
    if (this.#pv.pv_converged() && !this.#stats.converged && !preview) {
      this.#stats.converged = true;
      this.#stats.convergedMs = performance.now() - this.#stats.restartedAt;
      this.#events.emit('converged', { frame, total, milliseconds: this.#stats.convergedMs });
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
    const k = this.#adapt.tiles(this.#jsSettings, this.#renderSize[0] * this.#renderSize[1],
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
