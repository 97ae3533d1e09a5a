// penumbra-prefilter --format ktx2 for other engines: the file it writes for a panorama is read
// in headless Chromium by ktx-parse (structure: format, faces, levels, data format descriptor,
// key/value data with the manifest) and by three.js's KTX2Loader (the texture three makes and
// uploads), whose texels match the same run's faces as Radiance HDR files (three's HDRLoader)
// within the RGBE files' own precision.
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { closeServer, launch, outDir, recordConsole, root, serve, withTimeout } from './harness.mjs';

const PREFILTER = process.env.PENUMBRA_PREFILTER ||
  join(root, 'build/tools/prefilter/penumbra-prefilter');
const SIZE = 16;      // faces 16, 8, 4: three levels
const LEVELS = 3;
const FACES = ['px', 'nx', 'py', 'ny', 'pz', 'nz'];
// RGBE keeps 8 bits of mantissa: a step is 2^-8 to 2^-7 of the largest channel (measured here:
// 0.0078), the KTX2 file's half floats 2^-11. A wrong face, row order or level moves texels by
// far more.
const REL_TOL = 0.012;

let server, browser;
const work = join(outDir, 'prefilter-ktx2');

const PAGE = `<!doctype html><meta charset="utf-8">
<script type="importmap">{"imports": {"three": "/three/build/three.module.js"}}</script>
<script type="module">
import * as THREE from 'three';
import { KTX2Loader } from '/three/examples/jsm/loaders/KTX2Loader.js';
import { HDRLoader } from '/three/examples/jsm/loaders/HDRLoader.js';
import { read } from '/ktx-parse/dist/ktx-parse.modern.js';
window.inspect = async (levels, faces) => {
  const buffer = await (await fetch('/env.ktx2')).arrayBuffer();
  const c = read(new Uint8Array(buffer));
  const text = (v) => typeof v === 'string' ? v : new TextDecoder().decode(v).replace(/\\0$/, '');
  const dfd = c.dataFormatDescriptor[0];
  const structure = {
    vkFormat: c.vkFormat, typeSize: c.typeSize, width: c.pixelWidth, height: c.pixelHeight,
    depth: c.pixelDepth, layers: c.layerCount, faces: c.faceCount, levels: c.levels.length,
    supercompression: c.supercompressionScheme, keys: Object.keys(c.keyValue).sort(),
    writer: text(c.keyValue.KTXwriter), manifest: text(c.keyValue['penumbra.environment']),
    colorModel: dfd.colorModel, primaries: dfd.colorPrimaries, transfer: dfd.transferFunction,
    bytesPlane0: dfd.bytesPlane[0],
    samples: dfd.samples.map((s) => ({ bitOffset: s.bitOffset, bitLength: s.bitLength,
                                        channelType: s.channelType })),
  };
  const renderer = new THREE.WebGLRenderer({ canvas: document.createElement('canvas') });
  const loader = new KTX2Loader();
  loader.detectSupport(renderer);
  const texture = await new Promise((ok, fail) => loader.parse(buffer, ok, fail));
  renderer.initTexture(texture);  // three uploads it as it would for a material
  const glError = renderer.getContext().getError();
  const hdr = new HDRLoader().setDataType(THREE.FloatType);
  let maxRel = 0, worst = '', alphaOk = true;
  for (let m = 0; m < levels; m++) {
    const halfs = texture.mipmaps[m].data;
    const n = texture.mipmaps[m].width;
    for (let f = 0; f < faces.length; f++) {
      const face = hdr.parse(await (await fetch('/faces/mip' + m + '_' + faces[f] + '.hdr')).arrayBuffer());
      for (let i = 0; i < n * n; i++) {
        const at = (f * n * n + i) * 4;
        const peak = Math.max(face.data[4 * i], face.data[4 * i + 1], face.data[4 * i + 2], 1e-3);
        for (let k = 0; k < 3; k++) {
          const rel = Math.abs(THREE.DataUtils.fromHalfFloat(halfs[at + k]) - face.data[4 * i + k]) / peak;
          if (rel > maxRel) { maxRel = rel; worst = 'mip ' + m + ' face ' + faces[f] + ' texel ' + i; }
        }
        if (THREE.DataUtils.fromHalfFloat(halfs[at + 3]) !== 1) alphaOk = false;
      }
    }
  }
  return { structure, glError, maxRel, worst, alphaOk, type: texture.type,
           halfFloatType: THREE.HalfFloatType, format: texture.format, rgbaFormat: THREE.RGBAFormat,
           mipmaps: texture.mipmaps.map((l) => [l.width, l.height, l.data.length]) };
};
window.ready = true;
</script>`;

before(async () => {
  assert.ok(existsSync(PREFILTER), `${PREFILTER} is not built (ninja -C build)`);
  rmSync(work, { recursive: true, force: true });
  mkdirSync(work, { recursive: true });
  const r = spawnSync(PREFILTER, [join(root, 'assets/env/studio_sky.hdr'), '-o', work,
                                  '--size', String(SIZE), '--samples', '16',
                                  '--format', 'ktx2,faces-hdr', '-q'],
                      { encoding: 'utf8', timeout: 60_000 });
  assert.equal(r.status, 0, `penumbra-prefilter failed: ${r.stderr}`);
  writeFileSync(join(work, 'page.html'), PAGE);
  const extra = { '/page.html': join(work, 'page.html'), '/env.ktx2': join(work, 'environment.ktx2') };
  for (let m = 0; m < LEVELS; m++) {
    for (const f of FACES) extra[`/faces/mip${m}_${f}.hdr`] = join(work, `faces/mip${m}_${f}.hdr`);
  }
  server = await serve(join(root, 'web/node_modules'), extra);
  browser = await launch();
}, { timeout: 90_000 });

after(async () => {
  if (browser) await browser.close();
  closeServer(server);
});

test('a KTX2 environment from penumbra-prefilter reads in ktx-parse and three.js with its texels', { timeout: 60_000 }, async () => {
  const page = await browser.context.newPage();
  const lines = recordConsole(page);
  try {
    await page.goto(`http://127.0.0.1:${server.address().port}/page.html`, { timeout: 20_000 });
    await page.waitForFunction(() => window.ready === true, null, { timeout: 20_000 });
    const r = await withTimeout(page.evaluate(([l, f]) => window.inspect(l, f), [LEVELS, FACES]),
                                40_000, 'inspect');
    const s = r.structure;
    assert.equal(s.vkFormat, 97, 'VK_FORMAT_R16G16B16A16_SFLOAT');
    assert.deepEqual([s.typeSize, s.width, s.height, s.depth, s.layers, s.faces, s.levels,
                      s.supercompression], [2, SIZE, SIZE, 0, 0, 6, LEVELS, 0]);
    assert.deepEqual([s.colorModel, s.primaries, s.transfer, s.bytesPlane0], [1, 1, 1, 8],
                     'RGBSDA, BT.709, linear, 8 bytes a texel');
    assert.deepEqual(s.samples.map((x) => [x.bitOffset, x.bitLength, x.channelType]),
                     [[0, 15, 0xC0], [16, 15, 0xC1], [32, 15, 0xC2], [48, 15, 0xCF]],
                     'four signed float 16-bit samples R, G, B, A');
    assert.deepEqual(s.keys, ['KTXwriter', 'penumbra.environment']);
    assert.match(s.writer, /^penumbra-prefilter /);
    const manifest = JSON.parse(s.manifest);
    assert.equal(manifest.faceSize, SIZE);
    assert.equal(manifest.mipCount, LEVELS);
    assert.equal(manifest.roughness.length, LEVELS);
    assert.equal(manifest.sh.coefficients.length, 9);
    assert.equal(r.type, r.halfFloatType, 'three makes a half-float texture');
    assert.equal(r.format, r.rgbaFormat);
    assert.deepEqual(r.mipmaps, [[16, 16, 16 * 16 * 6 * 4], [8, 8, 8 * 8 * 6 * 4], [4, 4, 4 * 4 * 6 * 4]]);
    assert.equal(r.glError, 0, 'three uploads it without a GL error');
    assert.ok(r.alphaOk, 'alpha is 1');
    console.log(`KTX2 against the HDR faces: max relative difference ${r.maxRel.toFixed(5)} (${r.worst})`);
    assert.ok(r.maxRel <= REL_TOL, `texels differ by ${r.maxRel} (${r.worst}) > ${REL_TOL}`);
  } catch (e) {
    e.message += `\n${lines.slice(-20).join('\n')}`;
    throw e;
  } finally {
    await page.close().catch(() => {});
  }
});
