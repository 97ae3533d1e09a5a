// The viewer page (index.html): creates a Penumbra viewer on the full-window canvas, loads the
// scene and environment named in the URL (default: the Cornell box), and wires the progress
// line, the settings panel, drag and drop, the file picker, the screenshot button and the
// context-loss notices to the JS API. window.penumbraPage exposes the viewer and a log of what
// happened, for the browser tests (web/tests/viewer.test.mjs).
import Penumbra from './lib/penumbra.mjs';
import { ProgressMeter } from './lib/progress.mjs';

const DEFAULT_SCENE = 'assets/cornell_box/cornell_box.json';
const $ = (id) => document.getElementById(id);
const query = new URLSearchParams(location.search);

// What the tests read: errors shown, progress frames seen (bounded), counters.
const page = {
  viewer: null, ready: false, errors: [], progressLog: [], percents: [], convergedCount: 0,
  lostCount: 0, restoredCount: 0, sceneName: null, loading: null,
  statusWords: [],  // the status line's first word each time it changes (bounded)
};
window.penumbraPage = page;

// ---- messages ---------------------------------------------------------------------------------

function showMessage(text, { kind = 'error', id, timeoutMs } = {}) {
  if (id) $(`msg-${id}`)?.remove();
  const box = document.createElement('div');
  box.className = `message ${kind}`;
  if (id) box.id = `msg-${id}`;
  box.textContent = text;
  const close = document.createElement('button');
  close.type = 'button';
  close.textContent = '×';
  close.title = 'Dismiss';
  close.onclick = () => box.remove();
  box.append(close);
  $('messages').append(box);
  while ($('messages').children.length > 4) $('messages').firstChild.remove();
  if (timeoutMs) setTimeout(() => box.remove(), timeoutMs);
}

function showError(e) {
  const text = e && e.message ? e.message : String(e);
  page.errors.push(text);
  showMessage(text);
}

// ---- progress line ----------------------------------------------------------------------------

// The progress line in words (issue #42): what the page is doing, how far, how long still.
// The detail line below it keeps the numbers (image size, time per frame) for the curious.
const meter = new ProgressMeter();

function statusLine(s) {
  if (page.loading) return `Loading ${page.loading}…`;
  if (!s.total) return 'No scene: open or drop a glTF file';
  const { percent, secondsLeft: left, done } = meter.update(s);
  // A phone's view done at the CSS size goes on at device pixels (viewer.state.stage).
  if (done) return s.stage === 'sharpening' ? 'Done · sharpening for this screen…' : 'Done';
  if (page.percents.at(-1) !== percent) page.percents.push(percent);
  if (page.percents.length > 2000) page.percents.splice(0, 1000);
  // An automatic view's total is an estimate, so the time left is too: say it roughly.
  const eta = left === null ? '' : left >= 1
    ? `, about ${left < 10 ? left.toFixed(0) : (Math.round(left / 5) * 5).toFixed(0)} s left`
    : ', almost done';
  return `Refining: ${percent} %${eta}`;
}

function renderProgress(viewer) {
  const s = viewer.state;
  // A playing animation shows each pose's first frame: there is nothing to refine meanwhile.
  const a = viewer.animation;
  const clip = a.playing ? a.animations[a.index] : null;
  const status = clip ? `Playing ${clip.name || `animation ${a.index}`} · ${a.time.toFixed(1)} s`
    : statusLine(s);
  const word = status.split(/[ :]/)[0];
  if (page.statusWords.at(-1) !== word && page.statusWords.length < 50) page.statusWords.push(word);
  $('progress').textContent = status;
  $('progress-fill').style.width = s.total ? `${s.converged ? 100 : page.percents.at(-1) ?? 0}%` : '0';
  $('progress-fill').classList.toggle('done', s.converged);
  if (!s.total) {
    $('detail').textContent = '';
    return;
  }
  const size = `${s.renderWidth}×${s.renderHeight}` +
               (s.renderWidth !== s.canvasWidth ? ` of ${s.canvasWidth}×${s.canvasHeight}` : '');
  const lines = [`frame ${s.frame} of ${s.total} · ${size} pixels · ${s.frameMs.toFixed(0)} ms a frame` +
                 (s.split > 1 ? `, drawn in ${s.parts} parts` : '')];
  if (s.converged) lines.push(`done in ${(s.convergedMs / 1000).toFixed(1)} s`);
  $('detail').textContent = lines.join('\n');
}

// ---- settings panel ---------------------------------------------------------------------------

const form = $('panel');
const numberFields = ['fd', 'occlusionDistance', 'indirectClamp', 'exposure', 'budgetMs',
                      'resolutionScale', 'maxSplit', 'sunThreshold', 'shadowIntensity'];

function fillPanel(settings) {
  for (const el of form.elements) {
    if (!el.name || !(el.name in settings)) continue;
    if (el.type === 'checkbox') el.checked = Boolean(settings[el.name]);
    else if (el.name === 'resolutionScale') el.value = String(settings.resolutionScale);
    // Settings travel through float32 in wasm: 0.3 comes back as 0.30000001192092896.
    else if (typeof settings[el.name] === 'number') el.value = String(Number(settings[el.name].toPrecision(6)));
    else el.value = String(settings[el.name]);
  }
  form.elements.fdOut.value = Number(settings.fd).toFixed(2);
  form.elements.shadowIntensityOut.value = Number(settings.shadowIntensity).toFixed(1);
  form.elements.exposureOut.value = `${settings.exposure >= 0 ? '+' : ''}${Number(settings.exposure).toFixed(2)}`;
}

function wirePanel(viewer) {
  const apply = (el) => {
    if (!el.name || el.tagName === 'OUTPUT') return;
    let value = el.type === 'checkbox' ? el.checked : el.value;
    if (numberFields.includes(el.name)) value = Number(value);
    // frames: a number, or "auto" (also when left empty): until measured converged.
    if (el.name === 'frames') value = /^\s*(auto)?\s*$/i.test(value) ? 'auto' : Number(value);
    if (Number.isNaN(value)) return;
    viewer.setSettings({ [el.name]: value }).then(fillPanel, (e) => {
      showError(e);
      fillPanel(viewer.settings);  // put the field back to what is in effect
    });
  };
  // Ranges update live; typed numbers when committed (a half-typed value is not a setting).
  form.addEventListener('input', (e) => { if (e.target.type === 'range') apply(e.target); });
  form.addEventListener('change', (e) => { if (e.target.type !== 'range') apply(e.target); });
  form.addEventListener('submit', (e) => e.preventDefault());
  $('variant').addEventListener('change', (e) => {
    try {
      viewer.setVariant(e.target.value || null);
    } catch (err) {
      showError(err);
      fillVariants(viewer);
    }
  });
  // Animations (animation.mjs): choosing one shows its pose at 0 s; the button plays or pauses.
  $('animation').addEventListener('change', (e) => {
    const a = viewer.animation;
    try {
      if (e.target.value === '') a.rest(); else a.select(Number(e.target.value));
    } catch (err) {
      showError(err);
    }
    fillAnimations(viewer);
  });
  $('animation-play').addEventListener('click', () => {
    const a = viewer.animation;
    if (a.playing) a.pause(); else a.play();
    fillAnimations(viewer);
  });
  const toggle = $('toggle-panel');
  const setVisible = (v) => {
    form.classList.toggle('hidden', !v);
    toggle.setAttribute('aria-expanded', String(v));
  };
  toggle.onclick = () => setVisible(form.classList.contains('hidden'));
  $('close-panel').onclick = () => setVisible(false);
  // On a narrow (phone) screen the panel would cover half the view: it starts collapsed, and a
  // tap anywhere outside it (the view, the progress line) closes it again.
  const narrowQuery = window.matchMedia('(max-width: 600px)');
  const narrow = narrowQuery.matches;
  if (query.get('panel') === '0' || (narrow && query.get('panel') !== '1')) setVisible(false);
  document.addEventListener('pointerdown', (e) => {
    if (!narrowQuery.matches || form.classList.contains('hidden')) return;
    if (form.contains(e.target) || toggle.contains(e.target)) return;
    setVisible(false);
  });
}

// ---- files: drop and picker -------------------------------------------------------------------

const SCENE_EXT = /\.(glb|gltf|json)$/i;
const ENV_EXT = /\.(hdr|png|jpe?g)$/i;

// A dropped set: the first scene-like file is the scene and the others its resources; with no
// scene, an image is the environment. A lone .hdr next to a model is applied as environment too.
async function openFiles(viewer, fileList) {
  const files = [...fileList];
  if (!files.length) return;
  const sceneFile = files.find((f) => SCENE_EXT.test(f.name)) ||
                    files.find((f) => !ENV_EXT.test(f.name));  // unknown type: let the loader judge
  const envFiles = files.filter((f) => /\.hdr$/i.test(f.name) ||
                                       (!sceneFile && ENV_EXT.test(f.name)));
  // One start per load: nothing is drawn until the scene and its environment are both set.
  viewer.pause();
  try {
    if (sceneFile) {
      const resources = Object.fromEntries(files.filter((f) => f !== sceneFile).map((f) => [f.name, f]));
      await loadScene(viewer, sceneFile, { name: sceneFile.name, resources });
    }
    if (envFiles.length === 1 && !/\.json$/i.test(sceneFile?.name || '')) {
      showMessage(`prefiltering ${envFiles[0].name}…`, { kind: 'info', id: 'env', timeoutMs: 4000 });
      await viewer.setEnvironment(envFiles[0], { name: envFiles[0].name });
      $('msg-env')?.remove();
    }
  } catch (e) {
    $('msg-env')?.remove();
    showError(e);
  } finally {
    viewer.resume();
  }
}

// The panel's variant picker (KHR_materials_variants): shown only for a model that has some.
function fillVariants(viewer) {
  const scene = viewer.info.scene || {};
  const names = scene.variants || [];
  const select = $('variant');
  select.replaceChildren(select.options[0]);
  for (const name of names) select.add(new Option(name, name));
  select.value = scene.variant ?? '';
  $('variant-row').hidden = names.length === 0;
}

// The panel's animation picker and play button: shown only for a model that has animations.
function fillAnimations(viewer) {
  const a = viewer.animation;
  const select = $('animation');
  select.replaceChildren(select.options[0]);
  a.animations.forEach((clip, i) => select.add(new Option(clip.name || `animation ${i}`, String(i))));
  select.value = a.index >= 0 ? String(a.index) : '';
  const play = $('animation-play');
  play.textContent = a.playing ? 'Pause' : 'Play';
  play.setAttribute('aria-pressed', String(a.playing));
  $('animation-row').hidden = a.animations.length === 0;
}

async function loadScene(viewer, source, options) {
  const name = typeof source === 'string' ? source.split(/[?#]/)[0].split('/').pop()
                                          : source?.name || 'the scene';
  page.loading = name;
  let info;
  try {
    info = await viewer.loadScene(source, options);
  } finally {
    page.loading = null;
  }
  page.sceneName = info.name;
  fillPanel(viewer.settings);
  fillVariants(viewer);
  fillAnimations(viewer);
  document.title = `${info.name} — Penumbra viewer`;
  // A good load clears the notes of earlier failures: the problem they named is gone.
  for (const note of [...$('messages').querySelectorAll('.message.error')]) note.remove();
  // Warnings usually start with the file's name already; do not say it twice.
  for (const w of info.warnings || []) {
    showMessage(w.startsWith(info.name) ? w : `${info.name}: ${w}`, { kind: 'info', timeoutMs: 8000 });
  }
  return info;
}

function wireFiles(viewer) {
  let depth = 0;
  const overlay = $('drop-overlay');
  window.addEventListener('dragenter', (e) => { e.preventDefault(); depth++; overlay.hidden = false; });
  window.addEventListener('dragleave', () => { if (--depth <= 0) { depth = 0; overlay.hidden = true; } });
  window.addEventListener('dragover', (e) => e.preventDefault());
  window.addEventListener('drop', (e) => {
    e.preventDefault();
    depth = 0;
    overlay.hidden = true;
    openFiles(viewer, e.dataTransfer ? e.dataTransfer.files : []);
  });
  $('open').onclick = () => $('file').click();
  $('file').onchange = (e) => { openFiles(viewer, e.target.files); e.target.value = ''; };
}

// ---- buttons ----------------------------------------------------------------------------------

function wireButtons(viewer) {
  $('reset').onclick = () => viewer.setCamera('reset').catch(showError);
  $('shot').onclick = async () => {
    try {
      const blob = await viewer.screenshot();
      const a = document.createElement('a');
      a.href = URL.createObjectURL(blob);
      a.download = `penumbra-${(page.sceneName || 'scene').replace(/\.\w+$/, '')}-f${viewer.state.frame}.png`;
      a.click();
      setTimeout(() => URL.revokeObjectURL(a.href), 10_000);
    } catch (e) {
      showError(e);
    }
  };
}

// ---- start ------------------------------------------------------------------------------------

function numberParam(name) {
  const v = query.get(name);
  return v === null || v === '' ? undefined : Number(v);
}

async function main() {
  const options = {
    forceHalfFloat: query.get('halfFloat') === '1',
    budgetMs: numberParam('budget'),
    resolutionScale: numberParam('scale'),
    pixelRatio: numberParam('pixelRatio'),
    maxPixelRatio: numberParam('maxPixelRatio'),
    maxSplit: numberParam('split'),
    minStillScale: numberParam('minStillScale'),
    minMotionScale: numberParam('minMotionScale'),
  };
  // adaptive=0: the still image keeps the canvas's full size (tests comparing exact sizes).
  if (query.get('adaptive')) options.adaptiveResolution = query.get('adaptive') !== '0';
  // devicePixels=0: a phone's still view stays at the CSS size (no sharpening stage).
  if (query.get('devicePixels')) options.devicePixels = query.get('devicePixels') !== '0';
  const overrides = { frames: query.get('frames') === 'auto' ? 'auto' : numberParam('frames'),
                      fd: numberParam('fd'),
                      exposure: numberParam('exposure'),
                      occlusionDistance: numberParam('occlusionDistance') };
  if (query.get('tonemap')) overrides.toneMapper = query.get('tonemap');
  if (query.get('ssgi')) overrides.screenSpaceIndirect = query.get('ssgi') !== '0';
  if (query.get('gi')) overrides.probeVolume = query.get('gi') !== '0';
  for (const o of [options, overrides]) {
    for (const k of Object.keys(o)) if (o[k] === undefined) delete o[k];
  }
  let viewer;
  try {
    viewer = await Penumbra.create($('canvas'), { ...options, ...overrides });
  } catch (e) {
    $('progress').textContent = 'not available';
    showError(e);
    page.fatal = e.message;
    return;
  }
  page.viewer = viewer;
  $('caps').textContent = `${viewer.info.context}\n${viewer.info.report}`.trim();
  viewer.on('progress', ({ frame, total }) => {
    page.progressLog.push(frame);
    if (page.progressLog.length > 2000) page.progressLog.splice(0, 1000);
    page.total = total;
  });
  viewer.on('converged', () => { page.convergedCount++; });
  viewer.on('error', showError);
  viewer.on('contextlost', () => {
    page.lostCount++;
    showMessage('WebGL context lost — waiting for the browser to restore it', { id: 'lost' });
  });
  viewer.on('contextrestored', () => {
    page.restoredCount++;
    $('msg-lost')?.remove();
    showMessage('WebGL context restored', { kind: 'info', id: 'restored', timeoutMs: 4000 });
    $('caps').textContent = `${viewer.info.context}\n${viewer.info.report}`.trim();
  });
  // The progress line redraws at display rate, independently of the render loop's events.
  const redraw = () => { renderProgress(viewer); requestAnimationFrame(redraw); };
  requestAnimationFrame(redraw);

  wirePanel(viewer);
  wireFiles(viewer);
  wireButtons(viewer);
  fillPanel(viewer.settings);

  const sceneUrl = query.get('scene') || DEFAULT_SCENE;
  // One start per load: the scene, its variant and ?env= are all set before frame 1 (drawing
  // the studio-lit scene first and restarting for the HDR showed noise twice).
  viewer.pause();
  try {
    await loadScene(viewer, sceneUrl);
    // ?variant=NAME: a KHR_materials_variants variant of the scene.
    if (query.get('variant')) {
      viewer.setVariant(query.get('variant'));
      fillVariants(viewer);
    }
    // ?animation=NAME: plays that animation (as the element's autoplay and animation-name).
    if (query.get('animation')) {
      viewer.animation.select(query.get('animation'));
      viewer.animation.play();
      fillAnimations(viewer);
    }
  } catch (e) {
    showError(e);
  }
  const envUrl = query.get('env');
  if (envUrl) {
    try {
      showMessage(`loading ${envUrl}…`, { kind: 'info', id: 'env' });
      await viewer.setEnvironment(envUrl);
    } catch (e) {
      showError(e);
    } finally {
      $('msg-env')?.remove();
    }
  }
  viewer.resume();
  page.ready = true;
}

main().catch((e) => { showError(e); page.fatal = String(e); });
