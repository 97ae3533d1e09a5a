// Benchmark (prints only; not part of tools/test-web): the first seconds in headless Chromium on
// SwiftShader (a CPU "GPU"), issue #36's browser figures.
//
//   node web/tests/bench_first_light.mjs [--runs 2] [--timeout 180] [--start both]
//       [--only both|default|square|phone] [--query K=V&...]
// (Serves web/dist, made by tools/build-web; PENUMBRA_WEB_DIST points at another build.)
//
// --start: "fresh", the page opened the moment the browser has launched; "running", in a
// browser that has shown an ordinary page (text, form controls, rounded boxes; another origin,
// no WebGL) and then sat idle for --settle seconds, as a person's browser has; "both" (the
// default) prints each. A fresh browser is still starting: its GPU process sets up SwiftShader
// and compiles the compositor's own shaders for the first page it paints, about 0.5 s of the
// figures that a running browser has paid long before.
//
// 1. The default page (the Cornell box, lit only by its own lamp) on a phone viewport
//    (390x844, deviceScaleFactor 3, touch): from navigation, the first presented frame, the
//    first whose displayed mean reaches 10 % and 50 % of the converged image's, and
//    convergence. The canvas is sampled every animation frame (a 32x32 copy), so the figures
//    include that small cost.
// 2. A 2-triangle textured square under an HDR (studio_sky.hdr), frames "auto", at 512x512:
//    from navigation to the viewer's 'converged', and the frames it took.
// 3. Issue #59's phone figures (--only phone): the square and, where the sample models are
//    beside the repository (../shared/gltf-sample-assets, else skipped), DamagedHelmet under the
//    same HDR, on the phone viewport: from navigation to 'converged' (the page's "Done") and to
//    'sharpened' (the still image at device pixels), and the frames each took.
import { existsSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

import { closeServer, dist, root, serve, withPage } from './harness.mjs';

const args = process.argv.slice(2);
const arg = (name, def) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 && args[i + 1] ? args[i + 1] : def;
};
const runs = Number(arg('runs', 2));
const timeoutMs = Number(arg('timeout', 180)) * 1000;
const starts = arg('start', 'both') === 'both' ? ['fresh', 'running'] : [arg('start', 'both')];
const settleMs = Number(arg('settle', 3)) * 1000;
// Which measurements: default, square or both; --query adds URL parameters to both pages.
const only = arg('only', 'both');
const extraQuery = arg('query', '');

// Samples the canvas's mean brightness at every animation frame from the page's start, and
// records the viewer's progress and convergence, all against performance.now() (0 at
// navigation).
const PROBE = () => {
  const log = (window.__first = { samples: [], presents: [], converged: null, frames: 0,
                                  created: null, sharpened: null, sharpFrames: 0 });
  const small = document.createElement('canvas');
  small.width = small.height = 32;
  const ctx = small.getContext('2d', { willReadFrequently: true });
  let hooked = false;
  const tick = () => {
    const canvas = document.querySelector('canvas');
    const viewer = window.penumbraPage?.viewer;
    if (viewer && !hooked) {
      hooked = true;
      log.created = performance.now();
      viewer.on('progress', ({ frame }) => log.presents.push({ frame, t: performance.now() }));
      viewer.on('converged', ({ frame }) => {
        log.converged = performance.now();
        log.frames = frame;
      });
      viewer.on('sharpened', ({ frame }) => {
        log.sharpened = performance.now();
        log.sharpFrames = frame;
      });
    }
    if (canvas && canvas.width > 0) {
      ctx.drawImage(canvas, 0, 0, 32, 32);
      const d = ctx.getImageData(0, 0, 32, 32).data;
      let sum = 0;
      for (let i = 0; i < d.length; i += 4) sum += d[i] + d[i + 1] + d[i + 2];
      log.samples.push({ t: performance.now(), mean: sum / (3 * 32 * 32) });
    }
    if (log.converged === null) requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
};

// An ordinary page of another origin, for a running browser to have shown before.
const ORDINARY = `<!doctype html><html><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1"><title>An ordinary page</title>
<style>body{font:15px/1.4 system-ui,sans-serif;margin:16px;background:#fafafa;color:#222}
.card{background:#fff;border:1px solid #ddd;border-radius:8px;padding:12px;margin:12px 0;
box-shadow:0 1px 3px rgba(0,0,0,.15)}button{padding:6px 12px;border-radius:6px}</style></head>
<body><h1>News</h1><div class="card"><h2>A headline</h2><p>Some text, with <a href="#">a
link</a> and <b>bold</b> words. Lorem ipsum dolor sit amet, consectetur adipiscing elit.</p>
<button>Read more</button></div><div class="card"><label>Search <input type="text"></label>
<select><option>one</option></select> <input type="checkbox"> <input type="range"></div>
<div class="card" style="opacity:.8"><p>More text. Ut enim ad minim veniam.</p></div></body></html>`;

async function measure(server, query, device, start, ordinaryUrl, sharpened = false) {
  return withPage({ ...device, launchMs: 30_000 }, async (page) => {
    await page.addInitScript(PROBE);
    if (start === 'running') {
      await page.goto(ordinaryUrl, { timeout: 30_000 });
      await new Promise((r) => setTimeout(r, settleMs));
    }
    await page.goto(`http://127.0.0.1:${server.address().port}/index.html${query}`,
                    { timeout: 30_000 });
    // With `sharpened`: until the device-pixel stage is done too (or 10 s after converging,
    // where the page had nothing to sharpen).
    await page.waitForFunction((sharp) => {
      const f = window.__first;
      const done = f?.converged !== null && (!sharp || f.sharpened !== null ||
                                             performance.now() > f.converged + 10_000);
      return done || window.penumbraPage?.fatal || window.penumbraPage?.errors.length > 0;
    }, sharpened, { timeout: timeoutMs, polling: 250 });
    const r = await page.evaluate(() => ({ log: window.__first,
                                           errors: window.penumbraPage.errors }));
    if (r.errors.length) throw new Error(r.errors.join('; '));
    return r.log;
  });
}

// A square of two triangles, its base colour the lattice texture the glass scene uses.
function texturedSquare(dir) {
  const positions = new Float32Array([-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1]);
  const normals = new Float32Array([0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0]);
  const uvs = new Float32Array([0, 0, 4, 0, 4, 4, 0, 4]);
  const indices = new Uint16Array([0, 2, 1, 0, 3, 2]);
  const bin = Buffer.concat([positions, normals, uvs, indices].map((a) => Buffer.from(a.buffer)));
  const views = [[0, 48, 34962], [48, 48, 34962], [96, 32, 34962], [128, 12, 34963]];
  const gltf = {
    asset: { version: '2.0' },
    scene: 0,
    scenes: [{ nodes: [0, 1] }],
    nodes: [{ mesh: 0 },
            { camera: 0, translation: [0, 1.6, 2.2], rotation: [-0.3420201, 0, 0, 0.9396926] }],
    cameras: [{ type: 'perspective', perspective: { yfov: 0.8, znear: 0.05, aspectRatio: 1 } }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, NORMAL: 1, TEXCOORD_0: 2 },
                              indices: 3, material: 0 }] }],
    materials: [{ pbrMetallicRoughness: { baseColorTexture: { index: 0 }, metallicFactor: 0,
                                          roughnessFactor: 0.6 } }],
    textures: [{ source: 0 }],
    images: [{ uri: 'lattice.png' }],
    buffers: [{ byteLength: bin.length, uri: 'square.bin' }],
    bufferViews: views.map(([byteOffset, byteLength, target]) => ({ buffer: 0, byteOffset,
                                                                     byteLength, target })),
    accessors: [
      { bufferView: 0, componentType: 5126, count: 4, type: 'VEC3', min: [-1, 0, -1], max: [1, 0, 1] },
      { bufferView: 1, componentType: 5126, count: 4, type: 'VEC3' },
      { bufferView: 2, componentType: 5126, count: 4, type: 'VEC2' },
      { bufferView: 3, componentType: 5123, count: 6, type: 'SCALAR' },
    ],
  };
  writeFileSync(join(dir, 'square.gltf'), JSON.stringify(gltf));
  writeFileSync(join(dir, 'square.bin'), bin);
  return { '/bench/square.gltf': join(dir, 'square.gltf'), '/bench/square.bin': join(dir, 'square.bin'),
           '/bench/lattice.png': join(dist, 'assets/glass/lattice.png') };
}

const s = (ms) => (ms === null || ms === undefined ? 'never' : `${(ms / 1000).toFixed(2)} s`);
const firstAt = (samples, level) => samples.find((x) => x.mean >= level)?.t ?? null;

const tmp = mkdtempSync(join(tmpdir(), 'penumbra-bench-'));
const helmet = join(root, '..', 'shared', 'gltf-sample-assets', 'DamagedHelmet', 'DamagedHelmet.glb');
const server = await serve(dist, { ...texturedSquare(tmp), '/bench/DamagedHelmet.glb': helmet });
writeFileSync(join(tmp, 'ordinary.html'), ORDINARY);
const other = await serve(tmp, {});
const ordinaryUrl = `http://localhost:${other.address().port}/ordinary.html`;
try {
  readFileSync(join(dist, 'index.html'));
  const phone = { viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, isMobile: true,
                  hasTouch: true };
  for (const start of only === 'square' || only === 'phone' ? [] : starts) {
    console.log('Default page (Cornell box, own lamp only), phone 390x844 DPR 3, SwiftShader, ' +
                `${start} browser:`);
    for (let i = 0; i < runs; i++) {
      const log = await measure(server, extraQuery ? `?${extraQuery}` : '', phone, start,
                                ordinaryUrl);
      const final = log.samples.at(-1)?.mean ?? 0;
      console.log(`  run ${i + 1}: viewer created ${s(log.created)}, ` +
                  `first frame ${s(log.presents[0]?.t)}, ` +
                  `10 % of converged ${s(firstAt(log.samples, 0.1 * final))}, ` +
                  `50 % ${s(firstAt(log.samples, 0.5 * final))}, ` +
                  `converged ${s(log.converged)} (${log.frames} frames)`);
    }
  }
  const square = { viewport: { width: 512, height: 512 }, deviceScaleFactor: 1 };
  for (const start of only === 'default' || only === 'phone' ? [] : starts) {
    console.log('Textured 2-triangle square under studio_sky.hdr, frames auto, 512x512, ' +
                `${start} browser:`);
    for (let i = 0; i < runs; i++) {
      const log = await measure(server, '?scene=bench/square.gltf&env=assets/env/studio_sky.hdr' +
                                        `&frames=auto&panel=0${extraQuery ? `&${extraQuery}` : ''}`,
                                square, start, ordinaryUrl);
      console.log(`  run ${i + 1}: viewer created ${s(log.created)}, ` +
                  `first frame ${s(log.presents[0]?.t)}, converged ${s(log.converged)} ` +
                  `(${log.frames} frames)`);
    }
  }
  const models = [['Textured 2-triangle square', 'bench/square.gltf']];
  if (existsSync(helmet)) models.push(['DamagedHelmet', 'bench/DamagedHelmet.glb']);
  else if (only === 'phone') console.log(`(${helmet} is absent: DamagedHelmet skipped)`);
  for (const start of only === 'phone' ? starts : []) {
    for (const [name, path] of models) {
      console.log(`${name} under studio_sky.hdr, frames auto, phone 390x844 DPR 3, ${start} browser:`);
      for (let i = 0; i < runs; i++) {
        const log = await measure(server, `?scene=${path}&env=assets/env/studio_sky.hdr&frames=auto` +
                                          `${extraQuery ? `&${extraQuery}` : ''}`,
                                  phone, start, ordinaryUrl, true);
        console.log(`  run ${i + 1}: first frame ${s(log.presents[0]?.t)}, Done ${s(log.converged)} ` +
                    `(${log.frames} frames), at device pixels ${s(log.sharpened)} ` +
                    `(${log.sharpFrames} frames)`);
      }
    }
  }
} finally {
  closeServer(server);
  closeServer(other);
}
