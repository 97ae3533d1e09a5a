// Animation playback in <penumbra-viewer> (web/lib/animation.mjs, Renderer::setPose), against
// what model-viewer documents for autoplay, animation-name, play(), pause(), currentTime and
// availableAnimations: an animated model with `autoplay` plays (the canvas changes while it
// plays), pause() stops it (the canvas stops changing and the view converges), and the paused
// pose at currentTime T converges to the picture native penumbra-render draws with
// --animation 0 --time T (and not to its rest pose); `play` and `pause` fire once each. A name
// the model lacks is one `error` event naming the model's animations; another animation chosen
// while playing fades in (animation-crossfade-duration) and plays.
//
// The model is written by before(): a red strip skinned to two joints (the second bends), and
// a red card that moves up and lifts a corner (a morph target), one animation "wave" over 2 s.
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { blocks, closeServer, diff, dist, fmt, launch, nativeRender, outDir, pixels,
         recordConsole, serve, withTimeout } from './harness.mjs';

const WIDTH = 160, HEIGHT = 120;
const FRAMES = 16;
const WAIT_MS = 90_000;
const TEST_MS = 240_000;
const PAUSED_AT = 0.75;  // seconds: the pose compared with native
// Canvas vs native (SwiftShader vs llvmpipe, display values in [0, 1]), as transparency.test.mjs:
// noise lands differently per pixel, so pixels get a mean bound and 8x8 blocks a tight one. The
// rest pose against the pose at 0.75 s differs by more than 0.03 in the blocks' mean.
const NATIVE_MEAN_TOL = 0.02;
const NATIVE_BLOCK_MEAN_TOL = 0.008;
// Two screenshots of a playing model 0.6 s apart differ by at least this (mean over pixels).
const PLAYING_MIN_CHANGE = 0.002;

// A glTF with its buffer as a data URI, from named float/uint8 arrays.
function animatedGltf() {
  const parts = [];
  const doc = { asset: { version: '2.0' }, accessors: [], bufferViews: [], buffers: [] };
  let offset = 0;
  const accessor = (array, type, componentType, extra = {}) => {
    const bytes = new Uint8Array(array.buffer);
    doc.bufferViews.push({ buffer: 0, byteOffset: offset, byteLength: bytes.length });
    parts.push(bytes);
    offset += bytes.length;
    const width = { SCALAR: 1, VEC3: 3, VEC4: 4, MAT4: 16 }[type];
    doc.accessors.push({ bufferView: doc.bufferViews.length - 1, componentType, type,
                         count: array.length / width, ...extra });
    return doc.accessors.length - 1;
  };
  const f32 = (v, type, extra) => accessor(new Float32Array(v), type, 5126, extra);
  const pos = [], nrm = [], joints = [], weights = [], idx = [];
  for (let i = 0; i < 6; ++i) {
    const x = 0.4 * i;
    for (const y of [0, 0.3]) {
      pos.push(x, y, 0);
      nrm.push(0, 0, 1);
      joints.push(0, 1, 0, 0);
      const w1 = Math.min(Math.max(x - 0.6, 0), 0.8) / 0.8;
      weights.push(1 - w1, w1, 0, 0);
    }
  }
  for (let i = 0; i < 5; ++i) idx.push(2 * i, 2 * i + 2, 2 * i + 3, 2 * i, 2 * i + 3, 2 * i + 1);
  const positions = f32(pos, 'VEC3', { min: [0, 0, 0], max: [2, 0.3, 0] });
  const strip = {
    attributes: { POSITION: positions, NORMAL: f32(nrm, 'VEC3'),
                  JOINTS_0: accessor(new Uint8Array(joints), 'VEC4', 5121),
                  WEIGHTS_0: f32(weights, 'VEC4') },
    indices: accessor(new Uint16Array(idx), 'SCALAR', 5123), material: 0 };
  const card = {
    attributes: { POSITION: f32([0, 0, 0, 0.8, 0, 0, 0.8, 0.8, 0, 0, 0.8, 0], 'VEC3',
                                { min: [0, 0, 0], max: [0.8, 0.8, 0] }),
                  NORMAL: f32([0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1], 'VEC3') },
    indices: accessor(new Uint16Array([0, 1, 2, 0, 2, 3]), 'SCALAR', 5123), material: 0,
    targets: [{ POSITION: f32([0, 0, 0, 0, 0, 0, 0, 0, 0.6, 0, 0, 0], 'VEC3',
                              { min: [0, 0, 0], max: [0, 0, 0.6] }) }] };
  doc.materials = [{ pbrMetallicRoughness: { baseColorFactor: [0.8, 0.1, 0.1, 1], metallicFactor: 0 } }];
  doc.meshes = [{ primitives: [strip] }, { primitives: [card], weights: [0] }];
  doc.nodes = [{ name: 'root', children: [1] }, { name: 'bend', translation: [1, 0, 0] },
               { mesh: 0, skin: 0 }, { mesh: 1, translation: [2.4, 0, 0] }];
  doc.skins = [{ joints: [0, 1], inverseBindMatrices:
    f32([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1], 'MAT4') }];
  doc.scenes = [{ nodes: [0, 2, 3] }];
  doc.scene = 0;
  const s = Math.sin(Math.PI / 7), c = Math.cos(Math.PI / 7);
  const times = f32([0, 1, 2], 'SCALAR', { min: [0], max: [2] });
  doc.animations = [{
    name: 'wave',
    samplers: [{ input: times, output: f32([0, 0, 0, 1, 0, 0, s, c, 0, 0, -s, c], 'VEC4') },
               { input: times, output: f32([0, 1, 0.3], 'SCALAR') },
               { input: times, output: f32([2.4, 0, 0, 2.4, 0.5, 0, 2.6, 0.2, 0], 'VEC3') }],
    channels: [{ sampler: 0, target: { node: 1, path: 'rotation' } },
               { sampler: 1, target: { node: 3, path: 'weights' } },
               { sampler: 2, target: { node: 3, path: 'translation' } }],
  }, {
    name: 'lift',  // the card's corner up and down: what a crossfade from "wave" goes to
    samplers: [{ input: times, output: f32([0, 1, 0], 'SCALAR') }],
    channels: [{ sampler: 0, target: { node: 3, path: 'weights' } }],
  }];
  const all = new Uint8Array(offset);
  let at = 0;
  for (const p of parts) { all.set(p, at); at += p.length; }
  doc.buffers = [{ byteLength: offset,
                   uri: `data:application/octet-stream;base64,${Buffer.from(all).toString('base64')}` }];
  return doc;
}

const PAGE = `<!doctype html><meta charset="utf-8"><title>animation test</title>
<style>body { margin: 0; } penumbra-viewer { width: ${WIDTH}px; height: ${HEIGHT}px; }</style>
<script type="module">
  import './lib/element.mjs';
  window.log = { converged: 0, error: [] };
  window.ready = true;
</script>`;

let server, browser, model;
const consoleLines = [];
let reference, rest;

before(async () => {
  mkdirSync(outDir, { recursive: true });
  writeFileSync(join(outDir, 'animation-page.html'), PAGE);
  model = join(outDir, 'animated.gltf');
  writeFileSync(model, JSON.stringify(animatedGltf()));
  reference = nativeRender(model, WIDTH, HEIGHT, FRAMES, 'native-animated.png', null, consoleLines,
                           ['--animation', '0', '--time', String(PAUSED_AT)]);
  rest = nativeRender(model, WIDTH, HEIGHT, FRAMES, 'native-animated-rest.png', null, consoleLines);
  const extra = { '/animation.html': join(outDir, 'animation-page.html'), '/animated.gltf': model };
  if (reference) extra['/__animated.png'] = reference.path;
  if (rest) extra['/__rest.png'] = rest.path;
  server = await serve(dist, extra);
  browser = await launch({ viewport: { width: 400, height: 300 } });
}, { timeout: 90_000 });

after(async () => {
  if (browser) await browser.close();
  closeServer(server);
});

const shot = (pg) => pixels(pg, null, 'penumbra-viewer');
const meanDiff = (a, b) => diff(a, b).mean;

test('autoplay plays, pause() stops and converges at currentTime like native --time', { timeout: TEST_MS }, async () => {
  const pg = await withTimeout(browser.context.newPage(), 10_000, 'new page');
  recordConsole(pg, consoleLines);
  try {
    await pg.goto(`http://127.0.0.1:${server.address().port}/animation.html`, { timeout: 20_000 });
    await pg.waitForFunction(() => window.ready, null, { timeout: 20_000 });
    await pg.evaluate(([f]) => {
      const el = document.createElement('penumbra-viewer');
      el.setAttribute('src', 'animated.gltf');
      el.setAttribute('frames', String(f));
      el.setAttribute('autoplay', '');
      el.setAttribute('adaptive-resolution', 'false');  // the canvas's own size, as native's
      el.addEventListener('converged', () => window.log.converged++);
      window.log.play = 0;
      window.log.pause = 0;
      el.addEventListener('play', () => window.log.play++);
      el.addEventListener('pause', () => window.log.pause++);
      el.addEventListener('error', (e) => window.log.error.push(e.detail.message));
      window.log.loaded = new Promise((ok) => el.addEventListener('load', ok, { once: true }));
      document.body.append(el);
    }, [FRAMES]);
    await withTimeout(pg.evaluate(() => window.log.loaded.then(() => true)), WAIT_MS, 'load');
    const info = await pg.evaluate(() => {
      const el = document.querySelector('penumbra-viewer');
      return { names: el.availableAnimations, duration: el.duration };
    });
    assert.deepEqual(info.names, ['wave', 'lift']);
    assert.ok(Math.abs(info.duration - 2) < 1e-6, `duration ${info.duration}`);
    // Playing: the time advances and the canvas changes.
    await pg.waitForFunction(() => document.querySelector('penumbra-viewer').currentTime > 0.2,
                             null, { timeout: WAIT_MS, polling: 100 });
    assert.equal(await pg.evaluate(() => document.querySelector('penumbra-viewer').paused), false);
    // (A moving view's preview size may still settle: shots of one size.)
    let moved = 0;
    for (let tries = 0; tries < 10; ++tries) {
      const a = await shot(pg);
      await pg.waitForTimeout(600);
      const b = await shot(pg);
      if (a.width !== b.width) continue;
      moved = meanDiff(a, b);
      break;
    }
    console.log(`# playing: canvas change over 0.6 s ${moved.toFixed(4)}`);
    assert.ok(moved >= PLAYING_MIN_CHANGE, `the canvas did not change while playing (${moved})`);
    // Paused at PAUSED_AT: the view converges at the canvas's size and stays.
    await pg.evaluate((t) => {
      const el = document.querySelector('penumbra-viewer');
      el.pause();
      el.currentTime = t;
    }, PAUSED_AT);
    await pg.waitForFunction(([w, h]) => {
      const el = document.querySelector('penumbra-viewer');
      const c = el.shadowRoot.querySelector('canvas');
      const s = el.viewer.state;
      return (s.converged && c.width === w && c.height === h) || window.log.error.length > 0;
    }, [WIDTH, HEIGHT], { timeout: WAIT_MS, polling: 100 });
    assert.deepEqual(await pg.evaluate(() => window.log.error), []);
    const state = await pg.evaluate(() => {
      const el = document.querySelector('penumbra-viewer');
      return { paused: el.paused, time: el.currentTime };
    });
    assert.equal(state.paused, true);
    assert.deepEqual(await pg.evaluate(() => [window.log.play, window.log.pause]), [1, 1],
                     'one play event (autoplay) and one pause event, as model-viewer fires');
    assert.ok(Math.abs(state.time - PAUSED_AT) < 1e-6, `currentTime ${state.time}`);
    const c = await shot(pg);
    await pg.waitForTimeout(500);
    const d = await shot(pg);
    assert.equal(meanDiff(c, d), 0, 'the paused, converged canvas does not change');
    await pg.screenshot({ path: join(outDir, 'animation-paused.png') });
    if (!reference) {
      console.log('# no native penumbra-render built: the paused pose not compared');
    } else {
      const png = (url) => pixels(pg, url);
      const ref = await png('/__animated.png');
      const px = diff(c, ref);
      const bl = diff(blocks(c, 8), blocks(ref, 8));
      console.log(`# paused at ${PAUSED_AT} s vs ${reference.source}: pixels ${fmt(px)}; 8x8 blocks ${fmt(bl)}`);
      assert.ok(px.mean <= NATIVE_MEAN_TOL, `pixels: mean > ${NATIVE_MEAN_TOL} (${fmt(px)})`);
      assert.ok(bl.mean <= NATIVE_BLOCK_MEAN_TOL, `blocks: mean > ${NATIVE_BLOCK_MEAN_TOL} (${fmt(bl)})`);
      // Not the rest pose: a viewer that ignored the animation would not get here.
      const still = diff(blocks(c, 8), blocks(await png('/__rest.png'), 8));
      console.log(`# paused canvas vs the native rest pose: 8x8 blocks ${fmt(still)}`);
      assert.ok(still.mean > 3 * NATIVE_BLOCK_MEAN_TOL, `the paused pose is the rest pose (${fmt(still)})`);
    }
    // A name the model lacks: one attribute error naming the one there is.
    await pg.evaluate(() => document.querySelector('penumbra-viewer').setAttribute('animation-name', 'jump'));
    await pg.waitForFunction(() => window.log.error.length > 0, null, { timeout: 10_000 });
    const errors = await pg.evaluate(() => window.log.error);
    assert.equal(errors.length, 1);
    assert.match(errors[0], /animation-name="jump".*wave, lift/);
    // Another animation while playing: it fades in (animation-crossfade-duration) and plays.
    await pg.evaluate(() => {
      const el = document.querySelector('penumbra-viewer');
      el.setAttribute('animation-crossfade-duration', '500');
      el.setAttribute('animation-name', 'lift');
      el.play();
    });
    await pg.waitForFunction(() => document.querySelector('penumbra-viewer').currentTime > 0.3,
                             null, { timeout: WAIT_MS, polling: 100 });
    assert.equal(await pg.evaluate(() => document.querySelector('penumbra-viewer').viewer.animation.index), 1);
    assert.equal((await pg.evaluate(() => window.log.error)).length, 1, 'no new error');
  } catch (e) {
    await pg.screenshot({ path: join(outDir, 'animation-failed.png') }).catch(() => {});
    e.message += `\n--- console ---\n${consoleLines.slice(-40).join('\n')}`;
    throw e;
  } finally {
    await pg.close().catch(() => {});
  }
});
