// Compressed meshes and textures in the browser (KHR_draco_mesh_compression,
// EXT_meshopt_compression, KHR_texture_basisu): the glass scene with a KTX2 texture renders as
// with its PNG; the
// product scene compressed by tools/assets/gen_compressed.mjs (no uncompressed fallback data;
// tools/build-web writes it to web/dist/assets/compressed/) renders like native
// penumbra-render of the same file; each page fetches only the decoder its file needs (and
// meshoptimizer's simplifier for a file with a mesh dense enough for a capture stand-in), and
// an uncompressed scene none but that; a malformed compressed buffer is a one-line error on the page and
// a rejected promise with a one-line message, and the previous scene keeps rendering.
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join, relative } from 'node:path';
import { blocks, closeServer, diff, dist, fmt, launch, nativeError, nativeRender, outDir, pixels,
         recordConsole, root, serve, withTimeout } from './harness.mjs';

const WIDTH = 240, HEIGHT = 160;  // the product camera's 3:2
const FRAMES = 17;
const TEST_MS = 90_000;
// Canvas vs native (SwiftShader vs llvmpipe, display values in [0, 1]). Both decode the same
// compressed bytes with the same algorithms (measured: pixels mean 0.0007, max 0.15 at a few
// edge pixels; 8x8 block means mean 0.0004, max 0.011), so the bounds are about five times
// that: tighter than the glass scene's (transparency.test.mjs). Undecoded or wrongly decoded
// geometry (a missing knot, normals not unpacked) moves block means by far more.
const NATIVE_MEAN_TOL = 0.005;
const NATIVE_BLOCK_MEAN_TOL = 0.002;
const NATIVE_BLOCK_MAX_TOL = 0.05;
const DECODERS = { draco: 'draco_decoder_gltf_nodejs.js', meshopt: 'meshopt_decoder.mjs',
                   basis: 'basis_transcoder.js', simplifier: 'meshopt_simplifier.mjs' };
// The glass scene with its lattice texture as KTX2 (UASTC) against the same page with the PNG:
// one renderer, so only the transcoded texels differ (measured: pixels mean 0.0000, max 0.0000;
// a lattice left untextured moves 8x8 blocks by more than 0.1).
const KTX2_MEAN_TOL = 0.001;
const KTX2_BLOCK_MAX_TOL = 0.01;

let server, browser;
const consoleLines = [];
const references = {};
const bad = {};

// The good .glb with its first compressed payload broken: Draco's 'DRACO' magic, or the
// meshopt vertex codec's header byte (0xa0, version 0) on the first compressed view.
function corrupted(kind) {
  const bytes = new Uint8Array(readFileSync(join(dist, `assets/compressed/product_${kind}.glb`)));
  const view = new DataView(bytes.buffer);
  const jsonLength = view.getUint32(12, true);
  const json = JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + jsonLength)));
  const bin = 20 + jsonLength + 8;
  if (kind === 'draco') {
    const at = bin + (json.bufferViews[0].byteOffset || 0);
    assert.equal(new TextDecoder().decode(bytes.subarray(at, at + 5)), 'DRACO');
    bytes[at + 4] = 'X'.charCodeAt(0);
  } else {
    const ext = json.bufferViews.map((v) => v.extensions.EXT_meshopt_compression)
      .find((m) => m.mode === 'ATTRIBUTES');
    const at = bin + (ext.byteOffset || 0);
    assert.equal(bytes[at], 0xa0);
    bytes[at] = 0xff;
  }
  return [...bytes];
}

before(async () => {
  mkdirSync(outDir, { recursive: true });
  const extra = {};
  for (const kind of ['draco', 'meshopt']) {
    const scene = relative(root, join(dist, `assets/compressed/product_${kind}.json`));
    references[kind] = nativeRender(scene, WIDTH, HEIGHT, FRAMES, `native-product-${kind}.png`,
                                    null, consoleLines);
    if (references[kind]) extra[`/__${kind}.png`] = references[kind].path;
    bad[kind] = corrupted(kind);
  }
  server = await serve(dist, extra);
  browser = await launch({ viewport: { width: WIDTH, height: HEIGHT } });
}, { timeout: 150_000 });

after(async () => {
  if (browser) await browser.close();
  closeServer(server);
});

// The decoder files this page has fetched.
const fetchedDecoders = (pg) => pg.evaluate((names) => {
  const urls = performance.getEntriesByType('resource').map((e) => e.name);
  return Object.keys(names).filter((k) => urls.some((u) => u.endsWith(`/decoders/${names[k]}`)));
}, DECODERS);

async function openPage(scene) {
  const pg = await withTimeout(browser.context.newPage(), 10_000, 'new page');
  recordConsole(pg, consoleLines);
  const url = `http://127.0.0.1:${server.address().port}/index.html` +
              `?scene=${scene}&frames=${FRAMES}&pixelRatio=1&panel=0&adaptive=0`;
  await pg.goto(url, { timeout: 20_000 });
  await pg.waitForFunction(() => window.penumbraPage && (window.penumbraPage.ready ||
                                                         window.penumbraPage.fatal),
                           null, { timeout: 30_000 });
  assert.equal(await pg.evaluate(() => window.penumbraPage.fatal), undefined);
  return pg;
}

for (const kind of ['draco', 'meshopt']) {
  test(`a ${kind}-compressed .glb without fallback data renders like native`, { timeout: TEST_MS }, async () => {
    let pg;
    try {
      pg = await openPage(`assets/compressed/product_${kind}.json`);
      assert.deepEqual(await pg.evaluate(() => window.penumbraPage.errors), []);
      await pg.waitForFunction(() => window.penumbraPage.convergedCount > 0 ||
                                     window.penumbraPage.errors.length > 0,
                               null, { timeout: 60_000 });
      assert.deepEqual(await pg.evaluate(() => window.penumbraPage.errors), []);
      const info = await pg.evaluate(() => window.penumbraPage.viewer.info.scene);
      assert.ok(info.triangles > 10_000, `the knot and the ball decoded (${info.triangles} triangles)`);
      // Only the decoder this file needs was fetched, and the simplifier: the knot's 24,576
      // triangles get a capture stand-in (renderer/src/scene/mesh_lod.h), as natively.
      assert.deepEqual(await fetchedDecoders(pg), [kind, 'simplifier']);
      const canvas = await pixels(pg);
      await pg.screenshot({ path: join(outDir, `compressed-${kind}.png`) });
      if (!references[kind]) {
        console.log('# no native penumbra-render built: canvas not compared');
        return;
      }
      const ref = await pixels(pg, `/__${kind}.png`);
      const d = diff(canvas, ref);
      const b = diff(blocks(canvas, 8), blocks(ref, 8));
      console.log(`# ${kind}: canvas vs ${references[kind].source}: pixels ${fmt(d)}; 8x8 blocks ${fmt(b)}`);
      assert.ok(d.mean <= NATIVE_MEAN_TOL, `pixels: mean > ${NATIVE_MEAN_TOL} (${fmt(d)})`);
      assert.ok(b.mean <= NATIVE_BLOCK_MEAN_TOL, `blocks: mean > ${NATIVE_BLOCK_MEAN_TOL} (${fmt(b)})`);
      assert.ok(b.max <= NATIVE_BLOCK_MAX_TOL, `blocks: max > ${NATIVE_BLOCK_MAX_TOL} (${fmt(b)})`);
    } catch (e) {
      await pg?.screenshot({ path: join(outDir, `compressed-${kind}-failed.png`) }).catch(() => {});
      e.message += `\n--- console ---\n${consoleLines.slice(-40).join('\n')}`;
      throw e;
    } finally {
      await pg?.close().catch(() => {});
    }
  });
}

test('a KTX2 texture without a fallback image transcodes in the browser like its PNG', { timeout: TEST_MS }, async () => {
  let pg;
  try {
    const canvases = {};
    for (const [name, scene] of [['png', 'assets/glass/glass.json'],
                                 ['ktx2', 'assets/compressed/glass_ktx2.json']]) {
      pg = await openPage(scene);
      await pg.waitForFunction(() => window.penumbraPage.convergedCount > 0 ||
                                     window.penumbraPage.errors.length > 0,
                               null, { timeout: 60_000 });
      assert.deepEqual(await pg.evaluate(() => window.penumbraPage.errors), []);
      // The transcoder is fetched for the KTX2 file only; the simplifier for both (the bubble's
      // 2208 triangles get a capture stand-in).
      assert.deepEqual(await fetchedDecoders(pg),
                       name === 'ktx2' ? ['basis', 'simplifier'] : ['simplifier']);
      canvases[name] = await pixels(pg);
      await pg.screenshot({ path: join(outDir, `compressed-glass-${name}.png`) });
      await pg.close();
      pg = null;
    }
    const lines = consoleLines.filter((l) => /^\[(warning|error)\].*(KTX2|basis)/i.test(l));
    assert.deepEqual(lines, [], 'no KTX2 warning');
    // SwiftShader samples ASTC: the UASTC texture goes to the GPU as ASTC 4x4 blocks.
    const formats = consoleLines.filter((l) => l.includes('[penumbra] KTX2 '));
    console.log(`# ${formats.join('; ')}`);
    const astc = await withTimeout(browser.context.newPage(), 10_000, 'new page').then(async (p) => {
      const has = await p.evaluate(() => !!document.createElement('canvas').getContext('webgl2')
        ?.getExtension('WEBGL_compressed_texture_astc'));
      await p.close();
      return has;
    });
    assert.ok(formats.length > 0, 'the transcoder reported its target');
    if (astc) assert.ok(formats.every((l) => l.includes('ASTC 4x4')), formats.join('; '));
    const d = diff(canvases.ktx2, canvases.png);
    const b = diff(blocks(canvases.ktx2, 8), blocks(canvases.png, 8));
    console.log(`# KTX2 vs PNG texture: pixels ${fmt(d)}; 8x8 blocks ${fmt(b)}`);
    assert.ok(d.mean <= KTX2_MEAN_TOL, `pixels: mean > ${KTX2_MEAN_TOL} (${fmt(d)})`);
    assert.ok(b.max <= KTX2_BLOCK_MAX_TOL, `blocks: max > ${KTX2_BLOCK_MAX_TOL} (${fmt(b)})`);
  } catch (e) {
    await pg?.screenshot({ path: join(outDir, 'compressed-ktx2-failed.png') }).catch(() => {});
    e.message += `\n--- console ---\n${consoleLines.slice(-40).join('\n')}`;
    throw e;
  } finally {
    await pg?.close().catch(() => {});
  }
});

test('a malformed compressed buffer is a one-line error on the page and in the promise', { timeout: TEST_MS }, async () => {
  let pg;
  try {
    pg = await openPage('assets/glass/glass.json');
    // An uncompressed scene fetches no decoder (the simplifier only for its dense bubble).
    assert.deepEqual(await fetchedDecoders(pg), ['simplifier']);
    // Dropped on the page.
    await pg.evaluate((bytes) => {
      const dt = new DataTransfer();
      dt.items.add(new File([new Uint8Array(bytes)], 'bad_draco.glb'));
      window.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
    }, bad.draco);
    await pg.waitForFunction(() => window.penumbraPage.errors.length > 0, null, { timeout: 20_000 });
    const shown = await pg.evaluate(() => window.penumbraPage.errors);
    assert.equal(shown.length, 1, `one error: ${shown}`);
    assert.match(shown[0], /^bad_draco\.glb: mesh \d+ primitive 0 \(KHR_draco_mesh_compression\): Draco decoding failed \(.+\)$/);
    assert.doesNotMatch(shown[0], /\n/);
    const text = await pg.textContent('#messages');
    assert.ok(text.includes(shown[0]), `the page shows it: ${text}`);
    // Through the API: rejected promises with one-line messages.
    const results = await pg.evaluate(async (b) => {
      const v = window.penumbraPage.viewer;
      const outcome = (p) => p.then(() => 'resolved', (e) => `${e.name}: ${e.message}`);
      return {
        meshopt: await outcome(v.loadScene(new Uint8Array(b.meshopt), { name: 'bad_meshopt.glb' })),
        draco: await outcome(v.loadScene(new Uint8Array(b.draco), { name: 'bad_draco.glb' })),
      };
    }, bad);
    assert.match(results.meshopt, /^PenumbraError: bad_meshopt\.glb: bufferView \d+ \(EXT_meshopt_compression\): the compressed data is malformed \(.+\)$/);
    assert.match(results.draco, /^PenumbraError: bad_draco\.glb: .*KHR_draco_mesh_compression.*Draco decoding failed/);
    for (const r of Object.values(results)) assert.doesNotMatch(r, /\n/);
    console.log(`# page: ${shown[0]}\n# promise: ${results.meshopt}\n# promise: ${results.draco}`);
    // Native penumbra-render says the same about the same bytes, but for the decoder's own
    // words in the last brackets (libdraco and meshoptimizer there, the npm builds here).
    const words = / \([^()]*\)$/;
    for (const [kind, message] of [['draco', results.draco], ['meshopt', results.meshopt]]) {
      const file = join(outDir, `bad_${kind}.glb`);
      writeFileSync(file, new Uint8Array(bad[kind]));
      const native = nativeError(file, consoleLines);
      if (native === null) continue;
      console.log(`# native: ${native}`);
      assert.equal(message.replace(/^PenumbraError: /, '').replace(words, ''),
                   native.replace(`${file}: `, `bad_${kind}.glb: `).replace(words, ''));
    }
    // The glass scene is still there and renders.
    const state = await pg.evaluate(() => window.penumbraPage.viewer.state);
    assert.ok(state.total > 0 && state.frame > 0, `still rendering: ${JSON.stringify(state)}`);
    assert.equal(await pg.evaluate(() => window.penumbraPage.sceneName), 'glass.json');
  } catch (e) {
    await pg?.screenshot({ path: join(outDir, 'compressed-errors-failed.png') }).catch(() => {});
    e.message += `\n--- console ---\n${consoleLines.slice(-40).join('\n')}`;
    throw e;
  } finally {
    await pg?.close().catch(() => {});
  }
});
