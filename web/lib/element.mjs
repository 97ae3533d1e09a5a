// <penumbra-viewer>: Penumbra as an HTML element, over the JS API (penumbra.mjs), with
// model-viewer's attribute names where they mean the same thing. docs/web/api.md lists every
// attribute and event, with model-viewer's name beside ours where they differ.
//
//   <script type="module">import 'penumbra-viewer';</script>
//   <penumbra-viewer src="chair.glb" environment-image="studio.hdr" camera-controls alt="A chair">
//
// It sizes like an image (300x150 unless CSS says otherwise) and its canvas fills it (the JS
// API follows the canvas's CSS size). It draws only while on screen (IntersectionObserver) and,
// as the JS API's loop sleeps once a view has converged, costs nothing while still. Penumbra's
// own settings are attributes too, named from the renderer's settings schema
// (occlusionDistance -> occlusion-distance), so a new setting needs no change here. Plain JS
// over the public API: nothing of this is compiled into the wasm module.
import { Penumbra, PenumbraError } from './penumbra.mjs';
import { ProgressMeter } from './progress.mjs';
import { applyAnimationAttributes, defineAnimationApi } from './animation.mjs';
import { AUTO_ROTATE_DEFAULTS } from './autorotate.mjs';
import { InteractionPrompt, PROMPT_STYLE, PROMPT_TEMPLATE } from './prompt.mjs';

export { Penumbra, PenumbraError, Viewer, version } from './penumbra.mjs';

// model-viewer's names for the settings whose derived name would differ.
const SETTING_ALIASES = { toneMapper: 'tone-mapping' };
// model-viewer's tone-mapping "neutral" is Khronos PBR Neutral, ours "pbr-neutral".
const TONE_ALIASES = { neutral: 'pbr-neutral' };
const CAMERA_ATTRIBUTES = ['camera-orbit', 'camera-target', 'field-of-view'];
// Attributes the element sets on itself (accessibility): no reconciling needed.
const OWN_ARIA = new Set(['role', 'aria-label', 'tabindex']);
const AUTO_ROTATE_ATTRIBUTES = ['auto-rotate', 'rotation-per-second', 'auto-rotate-delay'];
// model-viewer's attributes that Penumbra does not (yet) do: each warns once per element, so a
// page moved over from model-viewer hears why nothing happens (docs/web/api.md has the table).
export const UNSUPPORTED_ATTRIBUTES = Object.freeze({
  ar: 'AR is not supported', 'ar-modes': 'AR is not supported', 'ar-scale': 'AR is not supported',
  'ar-placement': 'AR is not supported', 'ios-src': 'AR is not supported',
  'xr-environment': 'AR is not supported',
  'shadow-softness': 'the ground shadow is as soft as the environment\'s light makes it (shadow-intensity)',
  'skybox-height': 'the skybox is infinitely far (no ground projection)',
  'min-camera-orbit': 'the orbit has no limits', 'max-camera-orbit': 'the orbit has no limits',
  'min-field-of-view': 'the field of view has no limits', 'max-field-of-view': 'the field of view has no limits',
  'disable-zoom': 'camera-controls cannot be restricted', 'disable-pan': 'camera-controls cannot be restricted',
  'disable-tap': 'camera-controls cannot be restricted', 'touch-action': 'camera-controls cannot be restricted',
  'orbit-sensitivity': 'camera-controls cannot be tuned', 'interpolation-decay': 'camera changes are immediate',
  orientation: 'the model cannot be turned', scale: 'the model cannot be scaled',
  'with-credentials': 'files are fetched without credentials',
});

// The attribute of a setting of the schema: camelCase to kebab-case, or model-viewer's name.
export function settingAttribute(key) {
  return SETTING_ALIASES[key] || key.replace(/[A-Z]/g, (c) => `-${c.toLowerCase()}`);
}

// An attribute's text as the value of schema entry `e` (setSettings checks ranges and names).
function parseSetting(e, text, attr) {
  const t = text.trim();
  if (e.type === 'bool') {
    if (t === '' || t === 'true') return true;  // a bare boolean attribute means true
    if (t === 'false') return false;
    throw new PenumbraError(`${attr}="${text}": must be true or false`);
  }
  if (e.type === 'toneMapper') return TONE_ALIASES[t] || t;
  if (e.auto && t === 'auto') return 'auto';
  const n = Number(t);
  if (t === '' || !Number.isFinite(n)) {
    throw new PenumbraError(`${attr}="${text}": not a number${e.auto ? ' or auto' : ''}`);
  }
  // The element's exposure is model-viewer's: a linear factor (1 leaves the image as it is);
  // the renderer's (the JS API, the CLI, scene files) is in EV.
  if (e.key === 'exposure') {
    if (n < 0) throw new PenumbraError(`${attr}="${text}": a factor of 0 or more (1 leaves the image as it is)`);
    return n > 0 ? Math.max(e.min ?? -32, Math.min(e.max ?? 32, Math.log2(n))) : (e.min ?? -32);
  }
  return n;
}

// "10deg", "0.5rad", "0.5" (radians, as model-viewer) -> radians; "2m", "20cm", "5mm", "2"
// (metres) -> metres; "50%" -> the fraction of `auto` (radius only). null when malformed.
const NUMBER = /^([+-]?(?:\d+\.?\d*|\.\d+)(?:e[+-]?\d+)?)([a-z%]*)$/i;
function parseUnit(token, kind, auto) {
  if (token === 'auto') return auto;
  const m = NUMBER.exec(token);
  if (!m) return null;
  const n = Number(m[1]), unit = m[2].toLowerCase();
  if (kind === 'angle') return { '': n, rad: n, deg: (n * Math.PI) / 180 }[unit] ?? null;
  const scale = { '': 1, m: 1, cm: 0.01, mm: 0.001 }[unit];
  if (scale !== undefined) return n * scale;
  return unit === '%' && kind === 'radius' ? (n / 100) * auto : null;
}

function parseList(attr, text, kinds, autos, example) {
  const tokens = text.trim().split(/\s+/);
  const values = tokens.length === kinds.length ? tokens.map((t, i) => parseUnit(t, kinds[i], autos[i])) : [];
  if (values.length !== kinds.length || values.some((v) => v === null || !Number.isFinite(v))) {
    throw new PenumbraError(`${attr}="${text}": expected ${example}`);
  }
  return values;
}

const TEMPLATE = `<style>
  :host { display: inline-block; position: relative; width: 300px; height: 150px; overflow: hidden; }
  :host([hidden]) { display: none; }
  canvas, .poster { position: absolute; inset: 0; width: 100%; height: 100%; display: block; }
  canvas { outline: none; }
  canvas.inert { pointer-events: none; }
  .poster { object-fit: contain; background: inherit; }
  [hidden] { display: none; }
  .bar { position: absolute; top: 0; left: 0; right: 0; height: 4px; pointer-events: none; }
  .bar > div { height: 100%; width: 0; background: rgba(0, 0, 0, 0.4); transition: width 0.1s; }
  ${PROMPT_STYLE}
</style><canvas part="canvas"></canvas><img part="poster" class="poster" alt="" hidden>
<slot name="progress-bar"><div part="default-progress-bar" class="bar" hidden><div
  part="default-progress-mask"></div></div></slot>${PROMPT_TEMPLATE}`;

export class PenumbraViewerElement extends HTMLElement {
  #canvas; #poster;
  #bar;     // the default download bar (slot "progress-bar" replaces it)
  #prompt;  // the interaction prompt (prompt.mjs)
  #viewer = null; #startFailed = false;
  #visible = false;            // on screen (IntersectionObserver)
  #interacted = false;         // reveal="interaction": the user clicked or pressed a key
  #drawn = false;              // a frame was drawn (the poster then goes, for good)
  #meter = new ProgressMeter();  // totalProgress: monotone, at most 0.25 a frame
  #loadedSrc = null;           // the URL of the scene shown
  #applied = null;             // what the viewer was last given, by attribute
  #cameraSet = false; #variantSet = false;
  #warned = new Set();         // unsupported attributes already warned about
  #modelVisible = false;       // model-visibility's last state
  #sceneCamera = null; #bounds = null;
  #busy = false; #again = false; #queued = false;
  #io = null; #mo = null; #disposeTimer = 0;

  constructor() {
    super();
    this.attachShadow({ mode: 'open' }).innerHTML = TEMPLATE;
    this.#canvas = this.shadowRoot.querySelector('canvas');
    this.#poster = this.shadowRoot.querySelector('.poster');
    this.#bar = this.shadowRoot.querySelector('.bar');
    this.#prompt = new InteractionPrompt(this, this.shadowRoot);
    this.#resetApplied();
    const reveal = (e) => {
      this.#prompt.touched();
      if (e.type === 'keydown' && e.key !== 'Enter' && e.key !== ' ') return;
      if (this.#interacted) return;
      this.#interacted = true;
      this.#schedule();
    };
    this.addEventListener('pointerdown', reveal);
    this.addEventListener('keydown', reveal);
  }

  // ---- public API ---------------------------------------------------------------------------

  // The JS API's viewer (penumbra.mjs) once created; null before (loading="lazy" off-screen)
  // and when WebGL2 is missing.
  get viewer() { return this.#viewer; }
  // A scene from `src` is loaded and shown.
  get loaded() { return this.#loadedSrc !== null && this.#loadedSrc === this.#applied.src; }
  // reveal="manual" (and "interaction" before the user acts): show the model now.
  dismissPoster() {
    this.#interacted = true;
    this.#schedule();
  }

  connectedCallback() {
    clearTimeout(this.#disposeTimer);
    if (!this.hasAttribute('role')) this.setAttribute('role', 'img');
    this.#updateAria();
    this.#mo ||= new MutationObserver((records) => {
      if (records.some((r) => r.attributeName === 'alt' || r.attributeName === 'reveal')) {
        this.#updateAria();
      }
      if (records.some((r) => !OWN_ARIA.has(r.attributeName))) this.#schedule();
    });
    this.#mo.observe(this, { attributes: true });
    this.#io = new IntersectionObserver((entries) => {
      this.#visible = entries[entries.length - 1].isIntersecting;
      this.#schedule();
    });
    this.#io.observe(this);
    this.#schedule();
  }

  disconnectedCallback() {
    this.#mo.disconnect();
    this.#io.disconnect();
    this.#visible = false;
    this.#viewer?.pause();
    // Moved in the DOM (removed and inserted in one task): keep the viewer; removed: free it.
    this.#disposeTimer = setTimeout(() => { if (!this.isConnected) this.#dispose(); }, 0);
  }

  // ---- reconciling the attributes with the viewer ---------------------------------------------

  #resetApplied() {
    // null: nothing set by the element (the scene's own or the API's default is in effect).
    this.#applied = { settings: new Map(), environment: null, skybox: null, src: null,
                      camera: null, variant: null, autoRotate: null, animation: null };
  }

  // Attribute changes arrive in batches (MutationObserver); one pass applies them all.
  #schedule() {
    if (this.#queued) return;
    this.#queued = true;
    queueMicrotask(() => {
      this.#queued = false;
      this.#run();
    });
  }

  // One pass at a time: a change during an asynchronous load runs another pass after it.
  async #run() {
    if (this.#busy) {
      this.#again = true;
      return;
    }
    this.#busy = true;
    try {
      do {
        this.#again = false;
        await this.#reconcile();
      } while (this.#again);
    } catch (e) {
      this.#fail('render', e);  // a bug here must not leave the element silent
    } finally {
      this.#busy = false;
    }
  }

  async #reconcile() {
    this.#canvas.classList.toggle('inert', !this.hasAttribute('camera-controls'));
    const poster = this.getAttribute('poster');
    if (poster !== null && this.#poster.getAttribute('src') !== poster) this.#poster.src = poster;
    this.#poster.hidden = !this.#posterShown();
    if (!this.isConnected) return;
    if (!this.#viewer) {
      if (this.#startFailed || (this.getAttribute('loading') === 'lazy' && !this.#visible)) return;
      if (!(await this.#start())) return;
    }
    const v = this.#viewer;
    await this.#applySettings(v);
    await this.#applyEnvironment(v);
    await this.#applySkybox(v);
    const loaded = await this.#applySrc(v);
    if (this.loaded) {
      this.#applyVariant(v);
      const bad = applyAnimationAttributes(this, v.animation, this.#applied);
      if (bad) this.#fail('attribute', new PenumbraError(bad));
      await this.#applyCamera(v);
    }
    this.#applyAutoRotate(v);
    this.#warnUnsupported();
    this.#updateRunning();
    // Not for a scene whose src was replaced meanwhile: the next pass loads the new one.
    if (loaded && this.loaded && this.#url(this.getAttribute('src') || '') === loaded) {
      this.#dispatch('load', { url: loaded, scene: v.info.scene });
    }
  }

  async #start() {
    try {
      // Orbit controls are always attached; without camera-controls the canvas gets no events.
      this.#viewer = await Penumbra.create(this.#canvas, { controls: true });
    } catch (e) {
      this.#startFailed = true;
      this.#fail('startfailure', e);
      return false;
    }
    const v = this.#viewer;
    v.pause();  // until on screen with a scene (#updateRunning)
    v.on('progress', (d) => {
      if (!this.#drawn) {
        this.#drawn = true;
        const posterWasShown = !this.#poster.hidden;
        this.#poster.hidden = !this.#posterShown();
        // model-viewer's: the poster, if there was one, is gone.
        if (posterWasShown && this.#poster.hidden) this.#dispatch('poster-dismissed', {});
      }
      this.#setModelVisible(true);
      const { percent } = this.#meter.update({ ...d, converged: false, frameMs: 0 });
      // The refinement; 'progress' is the download's, as model-viewer's.
      this.#dispatch('refine-progress', { ...d, totalProgress: percent / 100 });
    });
    v.on('converged', (d) => this.#dispatch('converged', d));
    v.on('camera', (d) => this.#dispatch('camera-change', { source: d.source }));
    v.on('sharpened', (d) => this.#dispatch('sharpened', d));
    v.on('error', (e) => this.#fail('render', e));
    return true;
  }

  // Renders only on screen, with a scene, once revealed: nothing is drawn behind a poster.
  #updateRunning() {
    const v = this.#viewer;
    if (!v) return;
    const run = this.isConnected && this.#visible && this.#revealed() && this.#loadedSrc !== null &&
                this.#applied.src !== null;
    this.#canvas.style.visibility = this.#applied.src !== null ? '' : 'hidden';
    if (this.#applied.src === null) this.#setModelVisible(false);
    if (run) v.resume();
    else v.pause();
  }

  #revealed() {
    const reveal = this.getAttribute('reveal');
    return (reveal !== 'interaction' && reveal !== 'manual') || this.#interacted;
  }

  #posterShown() {
    return this.hasAttribute('poster') && (!this.#revealed() || !this.#drawn);
  }

  async #applySettings(v) {
    const changes = {};
    for (const e of v.settingsSchema) {
      const attr = settingAttribute(e.key);
      const text = this.getAttribute(attr);
      if (text === (this.#applied.settings.get(attr) ?? null)) continue;
      this.#applied.settings.set(attr, text);
      try {
        changes[e.key] = text === null ? e.default : parseSetting(e, text, attr);  // removed: default
      } catch (err) {
        this.#fail('attribute', err);
      }
    }
    if (!Object.keys(changes).length) return;
    try {
      await v.setSettings(changes);
    } catch {
      // One at a time, so the good values apply and the bad one is named by its attribute.
      for (const [key, value] of Object.entries(changes)) {
        await v.setSettings({ [key]: value }).catch((err) => {
          const attr = settingAttribute(key);
          this.#fail('attribute', new PenumbraError(`${attr}="${this.getAttribute(attr)}": ${err.message}`));
        });
      }
    }
  }

  // model-viewer's skybox-image: the background apart from environment-image's lighting;
  // without environment-image it is the environment (#applyEnvironment), lighting too.
  #skyboxText() {
    const text = this.getAttribute('skybox-image');
    return text === null || text.trim() === '' ? null : text;
  }

  async #applySkybox(v) {
    const text = this.getAttribute('environment-image') === null ? null : this.#skyboxText();
    const want = text === null ? null : this.#url(text);
    if (want === this.#applied.skybox) return;
    this.#applied.skybox = want;
    try {
      await v.setSkybox(want);
    } catch (e) {
      this.#fail('loadfailure', e);
    }
  }

  // environment-image: a URL (packed .hdr or a panorama), "neutral" (the built-in studio, as
  // model-viewer's "neutral"), or none: the scene's own or the rule's.
  async #applyEnvironment(v) {
    const text = this.getAttribute('environment-image') ?? this.#skyboxText();
    const want = text === null ? null : text.trim() === 'neutral' ? 'neutral' : this.#url(text);
    if (want === this.#applied.environment) return;
    this.#applied.environment = want;
    try {
      await v.setEnvironment(want === null ? null : want === 'neutral' ? 'studio' : want);
      // A scene file's own environment comes back only by loading it again.
      if (want === null && v.info.scene?.sceneFile) this.#applied.src = null;
    } catch (e) {
      this.#fail('loadfailure', e);
    }
  }

  // Loads src when it changed. Returns the URL loaded by this call, else null.
  async #applySrc(v) {
    const text = this.getAttribute('src');
    const want = text === null || text.trim() === '' ? null : this.#url(text);
    if (want === this.#applied.src) return null;
    this.#applied.src = want;
    if (want === null) return null;  // the canvas is hidden (#updateRunning): nothing to show
    let info;
    try {
      this.#downloaded(0);
      info = await v.loadScene(want, { onProgress: (p) => this.#downloaded(p) });
      this.#downloaded(1);
    } catch (e) {
      this.#bar.hidden = true;
      this.#fail('loadfailure', e);  // the previous scene, if any, stays on screen
      return null;
    }
    this.#loadedSrc = want;
    this.#prompt.reset();  // a new model may prompt again
    this.#prompt.update(this.#modelVisible);
    this.#sceneCamera = v.camera;
    this.#bounds = info.bounds;
    this.#applied.camera = null;  // camera-* and variant-name apply to the new scene
    this.#cameraSet = false;
    this.#applied.variant = null;
    this.#applied.animation = null;
    this.#variantSet = false;
    // A scene file brings its own environment: environment-image, when given, replaces it.
    if (info.sceneFile && this.#applied.environment !== null) {
      this.#applied.environment = null;
      await this.#applyEnvironment(v);
    }
    return want;
  }

  // model-viewer's 'progress' {totalProgress} (0 as the download begins, 1 once loaded), and
  // the default bar showing it until then.
  #downloaded(p) {
    this.#dispatch('progress', { totalProgress: p });
    this.#bar.hidden = p >= 1;
    this.#bar.firstElementChild.style.width = `${Math.round(p * 100)}%`;
  }

  #applyVariant(v) {
    const name = this.getAttribute('variant-name');
    if (name === this.#applied.variant) return;  // null after a load: the scene's own choice
    this.#applied.variant = name;
    try {
      v.setVariant(name);
      this.#variantSet = name !== null;
    } catch (e) {
      this.#fail('attribute', new PenumbraError(`variant-name="${name}": ${e.message}`));
    }
  }

  // camera-orbit / camera-target / field-of-view; "auto" parts (and absent attributes) come
  // from the scene's own camera around the bounds' centre. None given: the scene's camera.
  async #applyCamera(v) {
    const texts = CAMERA_ATTRIBUTES.map((a) => this.getAttribute(a));
    const key = JSON.stringify(texts);
    if (key === this.#applied.camera) return;
    this.#applied.camera = key;
    try {
      if (texts.every((t) => t === null)) {
        if (this.#cameraSet) await v.setCamera('reset');
        this.#cameraSet = false;
        return;
      }
      await v.setCamera(this.#cameraFromAttributes(texts));
      this.#cameraSet = true;
    } catch (e) {
      this.#fail('attribute', e);
    }
  }

  // auto-rotate, rotation-per-second (an angle a second: "30deg", "0.2rad", "0.2"; model-viewer's
  // default pi/32 rad) and auto-rotate-delay (ms, 3000): autorotate.mjs.
  #applyAutoRotate(v) {
    const texts = AUTO_ROTATE_ATTRIBUTES.map((a) => this.getAttribute(a));
    const key = JSON.stringify(texts);
    if (key === this.#applied.autoRotate) return;
    this.#applied.autoRotate = key;
    const [on, rate, delay] = texts;
    try {
      const speed = rate === null || rate.trim() === 'auto' ? AUTO_ROTATE_DEFAULTS.speed
        : parseList('rotation-per-second', rate.replace(/\/s$/, ''), ['angle'], [AUTO_ROTATE_DEFAULTS.speed],
                    'an angle a second (e.g. 30deg)')[0];
      const delayMs = delay === null ? AUTO_ROTATE_DEFAULTS.delayMs : Number(delay);
      if (!(delayMs >= 0)) throw new PenumbraError(`auto-rotate-delay="${delay}": milliseconds, 0 or more`);
      v.setAutoRotate({ enabled: on !== null && on !== 'false', speed, delayMs });
    } catch (e) {
      this.#fail('attribute', e);
    }
  }

  // model-visibility {visible}: a model is drawn on the canvas (its first frame), or no more
  // (src removed), as model-viewer reports it.
  #setModelVisible(visible) {
    if (visible === this.#modelVisible) return;
    this.#modelVisible = visible;
    this.#prompt.update(visible);
    this.#dispatch('model-visibility', { visible });
  }

  // One console warning per element and attribute of model-viewer's that Penumbra lacks.
  #warnUnsupported() {
    for (const name of this.getAttributeNames()) {
      const why = UNSUPPORTED_ATTRIBUTES[name];
      if (why === undefined || this.#warned.has(name)) continue;
      this.#warned.add(name);
      console.warn(`[penumbra-viewer] ${name} is model-viewer's and not supported here: ${why}`);
    }
  }

  #cameraFromAttributes([orbit, target, fov]) {
    const b = this.#bounds;
    const centre = b ? b.min.map((m, i) => (m + b.max[i]) / 2) : [0, 0, 0];
    const t = target === null ? centre
      : parseList('camera-target', target, ['length', 'length', 'length'], centre, 'x y z (e.g. 0m 1m 0m or auto)');
    const eye = this.#sceneCamera.eye;
    const d = eye.map((e, i) => e - t[i]);
    const r0 = Math.hypot(...d) || 1;
    const auto = [Math.atan2(d[0], d[2]), Math.acos(Math.max(-1, Math.min(1, d[1] / r0))), r0];
    const [theta, phiIn, radius] = orbit === null ? auto
      : parseList('camera-orbit', orbit, ['angle', 'angle', 'radius'], auto, 'θ φ radius (e.g. 30deg 75deg 2m or auto)');
    const yfov = fov === null ? this.#sceneCamera.yfov
      : parseList('field-of-view', fov, ['angle'], [this.#sceneCamera.yfov], 'an angle (e.g. 45deg or auto)')[0];
    if (!(radius > 0)) throw new PenumbraError(`camera-orbit="${orbit}": the radius must be positive`);
    // Straight above or below, "up" would be parallel to the view: stop just short of it.
    const phi = Math.max(1e-3, Math.min(Math.PI - 1e-3, phiIn));
    const s = Math.sin(phi);
    return { eye: [t[0] + radius * s * Math.sin(theta), t[1] + radius * Math.cos(phi),
                   t[2] + radius * s * Math.cos(theta)],
             target: t, up: [0, 1, 0], yfov };
  }

  // ---- helpers ------------------------------------------------------------------------------

  #url(text) {
    return new URL(text.trim(), this.ownerDocument.baseURI).href;
  }

  #updateAria() {
    const alt = this.getAttribute('alt');
    this.setAttribute('aria-label', alt === null || alt === '' ? '3D model' : alt);
    // reveal="interaction" waits for a key press too, so the element must take focus.
    if (this.getAttribute('reveal') === 'interaction' && !this.hasAttribute('tabindex')) {
      this.setAttribute('tabindex', '0');
    }
  }

  #dispatch(type, detail) {
    this.dispatchEvent(new CustomEvent(type, { detail }));
  }

  // 'error' with {type, message, sourceError}: loadfailure (src, environment-image), attribute
  // (a bad value), startfailure (no WebGL2, the module did not load), render (the frame loop).
  #fail(type, e) {
    const message = e && e.message ? e.message : String(e);
    console.warn(`[penumbra-viewer] ${message}`);
    this.#dispatch('error', { type, message, sourceError: e });
  }

  #dispose() {
    this.#prompt.reset();
    if (!this.#viewer) return;
    this.#viewer.dispose();
    this.#viewer = null;
    // Release the WebGL context now (browsers keep a few), and start over on a fresh canvas
    // if the element is inserted again.
    this.#canvas.getContext('webgl2')?.getExtension('WEBGL_lose_context')?.loseContext();
    const canvas = document.createElement('canvas');
    canvas.setAttribute('part', 'canvas');
    this.#canvas.replaceWith(canvas);
    this.#canvas = canvas;
    this.#resetApplied();
    this.#loadedSrc = null;
    this.#drawn = false;
  }
}

// Properties that reflect attributes, as model-viewer's do: el.src = 'x.glb', el.exposure = 1.
const STRINGS = ['src', 'alt', 'poster', 'reveal', 'loading', 'environmentImage', 'skyboxImage',
                 'toneMapping',
                 'cameraOrbit', 'cameraTarget', 'fieldOfView', 'variantName', 'animationName'];
for (const prop of STRINGS) {
  const attr = settingAttribute(prop);
  Object.defineProperty(PenumbraViewerElement.prototype, prop, {
    get() { return this.getAttribute(attr); },
    set(v) { if (v === null || v === undefined) this.removeAttribute(attr); else this.setAttribute(attr, String(v)); },
  });
}
for (const [prop, attr] of [['cameraControls', 'camera-controls'], ['autoRotate', 'auto-rotate'],
                            ['autoplay', 'autoplay']]) {
  Object.defineProperty(PenumbraViewerElement.prototype, prop, {
    get() { return this.hasAttribute(attr); },
    set(v) { this.toggleAttribute(attr, Boolean(v)); },
  });
}
for (const prop of ['exposure', 'frames']) {
  Object.defineProperty(PenumbraViewerElement.prototype, prop, {
    get() {
      const t = this.getAttribute(prop);
      return t === null ? null : t.trim() === 'auto' ? 'auto' : Number(t);
    },
    set(v) { if (v === null || v === undefined) this.removeAttribute(prop); else this.setAttribute(prop, String(v)); },
  });
}

defineAnimationApi(PenumbraViewerElement.prototype);

if (!customElements.get('penumbra-viewer')) {
  customElements.define('penumbra-viewer', PenumbraViewerElement);
}
