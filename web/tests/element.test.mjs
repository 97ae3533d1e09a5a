// Browser tests of <penumbra-viewer> (web/lib/element.mjs, served from web/dist/lib) in Debian's
// headless Chromium: exposure changes the image without a restart, a src swap loads the new
// scene, `converged` comes once per view and the loop then sleeps, a bad src or attribute fires
// `error` with a one-line message and the element keeps working, loading="lazy" creates nothing
// and an eager element draws nothing while off-screen, the element sizes like an image and its
// canvas follows CSS, camera-controls gates the orbit, a poster with reveal="interaction" waits
// for a click, environment-image and the schema's settings apply as attributes, docs/web/api.md
// lists every settings attribute, and variant-name selects a KHR_materials_variants variant.
//
// Small on purpose: 160x120 elements (pixelRatio 1 in headless Chromium), the Cornell box and
// the material grid, frames="8". No bound on how fast anything answers: every wait has only a
// generous timeout (tools/test-web still runs it after the hand-off test, not beside it: its
// SwiftShader work slows the path tracer's shader compile past that test's wait).
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { closeServer, dist, launch, outDir, pixels, recordConsole, root, serve,
         withTimeout } from './harness.mjs';

const WAIT_MS = 90_000;   // SwiftShader on 2 shared cores: a module start and 8 frames take 3-20 s
const TEST_MS = 240_000;
const CORNELL = 'assets/cornell_box/cornell_box.gltf';
const GRID = 'assets/material_grid/material_grid.gltf';
const VARIANTS = 'assets/material_grid/element_variants.gltf';  // written by before()
const FLOATING = 'assets/material_grid/element_floating.gltf';  // the grid without its floor: before()

// The test page: loads the element module and records every element's events on it.
const PAGE = `<!doctype html><meta charset="utf-8"><title>penumbra-viewer test</title>
<style>body { margin: 0; } penumbra-viewer.small { width: 160px; height: 120px; }</style>
<script type="module">
  import { settingAttribute } from './lib/element.mjs';
  window.settingAttribute = settingAttribute;
  window.add = (html, parent = document.body) => {
    const t = document.createElement('template');
    t.innerHTML = html;
    const el = t.content.firstElementChild;
    el.log = { load: [], error: [], converged: 0, progress: 0 };
    el.addEventListener('load', (e) => el.log.load.push(e.detail.url));
    el.addEventListener('error', (e) => el.log.error.push({ type: e.detail.type, message: e.detail.message }));
    el.addEventListener('converged', () => el.log.converged++);
    el.addEventListener('refine-progress', () => el.log.progress++);  // frames drawn
    el.log.download = [];  // model-viewer's 'progress': the download's totalProgress
    el.addEventListener('progress', (e) => el.log.download.push(e.detail.totalProgress));
    el.addEventListener('load', () => el.log.download.push('load'));
    el.log.camera = [];
    el.log.visibility = [];
    el.log.posterDismissed = 0;
    el.addEventListener('camera-change', (e) => el.log.camera.push(e.detail.source));
    el.addEventListener('model-visibility', (e) => el.log.visibility.push(e.detail.visible));
    el.addEventListener('poster-dismissed', () => el.log.posterDismissed++);
    parent.append(el);
    return el;
  };
  window.frames = (n) => new Promise((ok) => {
    const next = () => (n-- <= 0 ? ok() : requestAnimationFrame(next));
    requestAnimationFrame(next);
  });
  window.ready = true;
</script>`;

let server, browser;
const consoleLines = [];

before(async () => {
  if (!existsSync(join(dist, 'lib/element.mjs'))) {
    throw new Error(`${dist}/lib/element.mjs is not built: run tools/build-web first`);
  }
  mkdirSync(outDir, { recursive: true });
  const page = join(outDir, 'element-page.html');
  writeFileSync(page, PAGE);
  // The material grid with one KHR_materials_variants variant, "shifted", that moves every
  // sphere's material twelve places on (beside the grid's own .bin, served from web/dist).
  const doc = JSON.parse(readFileSync(join(root, GRID), 'utf8'));
  const n = doc.materials.length;
  doc.extensionsUsed = [...(doc.extensionsUsed || []), 'KHR_materials_variants'];
  doc.extensions = { ...(doc.extensions || {}), KHR_materials_variants: { variants: [{ name: 'shifted' }] } };
  for (const mesh of doc.meshes) {
    for (const p of mesh.primitives) {
      p.extensions = { KHR_materials_variants: { mappings: [{ material: ((p.material ?? 0) + 12) % n, variants: [0] }] } };
    }
  }
  const variants = join(outDir, 'element-variants.gltf');
  writeFileSync(variants, JSON.stringify(doc));
  // The spheres alone, over nothing: what a ground shadow is for.
  const grid = JSON.parse(readFileSync(join(root, GRID), 'utf8'));
  const floor = grid.nodes.findIndex((n) => n.name === 'floor');
  grid.scenes[grid.scene ?? 0].nodes = grid.scenes[grid.scene ?? 0].nodes.filter((i) => i !== floor);
  const floating = join(outDir, 'element-floating.gltf');
  writeFileSync(floating, JSON.stringify(grid));
  server = await serve(dist, { '/element.html': page, [`/${VARIANTS}`]: variants, [`/${FLOATING}`]: floating });
  browser = await launch({ viewport: { width: 800, height: 600 } });
}, { timeout: 60_000 });

after(async () => {
  if (browser) await browser.close();
  closeServer(server);
});

// A fresh page with the test page loaded; on failure the message gets a screenshot and the
// console.
async function withTestPage(name, body) {
  const pg = await withTimeout(browser.context.newPage(), 10_000, 'new page');
  recordConsole(pg, consoleLines);
  try {
    await pg.goto(`http://127.0.0.1:${server.address().port}/element.html`, { timeout: 20_000 });
    await pg.waitForFunction(() => window.ready, null, { timeout: 20_000 });
    await body(pg);
  } catch (e) {
    const shot = join(outDir, `element-${name}.png`);
    await withTimeout(pg.screenshot({ path: shot, timeout: 8_000 }), 10_000, 'screenshot').catch(() => {});
    e.message += `\n--- console ---\n${consoleLines.slice(-30).join('\n')}\n--- screenshot: ${shot}`;
    throw e;
  } finally {
    await withTimeout(pg.close(), 10_000, 'close page').catch(() => {});
  }
}

// Waits until `el` (a selector) has fired `count` converged events, or an error.
async function waitConverged(pg, selector, count) {
  await pg.waitForFunction(([s, n]) => {
    const el = document.querySelector(s);
    return el.log.converged >= n || el.log.error.length > 0;
  }, [selector, count], { timeout: WAIT_MS, polling: 100 });
  const log = await pg.evaluate((s) => document.querySelector(s).log, selector);
  assert.deepEqual(log.error, [], `${selector}: no error while rendering`);
  return log;
}

// The displayed canvas (the context keeps its drawing buffer) as RGBA bytes.
const shot = (pg, selector) => pixels(pg, null, selector);

// What the page shows where an element is (the page behind a transparent canvas included): a
// screenshot of its box, decoded in the page.
async function onPage(pg, selector) {
  const box = await pg.evaluate((s) => {
    const r = document.querySelector(s).getBoundingClientRect();
    return { x: r.x, y: r.y, width: r.width, height: r.height };
  }, selector);
  const png = await pg.screenshot({ clip: box });
  return pixels(pg, `data:image/png;base64,${png.toString('base64')}`);
}

// Mean |a - b| over R, G, B in [0, 1], and the mean of an image.
function meanDiff(a, b) {
  assert.equal(a.data.length, b.data.length, 'same size');
  let sum = 0, n = 0;
  for (let i = 0; i < a.data.length; i += 4) {
    for (let c = 0; c < 3; c++, n++) sum += Math.abs(a.data[i + c] - b.data[i + c]);
  }
  return sum / n / 255;
}
function mean(img) {
  let sum = 0, n = 0;
  for (let i = 0; i < img.data.length; i += 4) for (let c = 0; c < 3; c++, n++) sum += img.data[i + c];
  return sum / n / 255;
}

test('exposure changes the image without a restart; converged once per view; src swap', { timeout: TEST_MS }, async () => {
  await withTestPage('views', async (pg) => {
    await pg.evaluate((src) => window.add(`<penumbra-viewer id="a" class="small" src="${src}" frames="8"
      adaptive-resolution="false" alt="A Cornell box"></penumbra-viewer>`), CORNELL);
    let log = await waitConverged(pg, '#a', 1);
    assert.equal(log.load.length, 1);
    assert.match(log.load[0], /cornell_box\.gltf$/);
    // Converged: the loop sleeps, and no frame is drawn or event fired any more.
    await pg.evaluate(() => window.frames(3));
    const asleep = await pg.evaluate(() => {
      const s = document.querySelector('#a').viewer.state;
      return { frame: s.frame, total: s.total, looping: s.looping, renderWidth: s.renderWidth,
               adaptive: document.querySelector('#a').viewer.settings.adaptiveResolution };
    });
    assert.deepEqual(asleep, { frame: 8, total: 8, looping: false, renderWidth: 160, adaptive: false });
    const progressBefore = log.progress;
    await pg.waitForTimeout(1500);
    log = await pg.evaluate(() => document.querySelector('#a').log);
    assert.equal(log.converged, 1, 'one converged event for one view');
    assert.equal(log.progress, progressBefore, 'no frames drawn after convergence');

    const dark = await shot(pg, '#a');
    // model-viewer's exposure: a linear factor, 4 = +2 EV in the renderer's setting.
    await pg.evaluate(() => document.querySelector('#a').setAttribute('exposure', '4'));
    await pg.waitForFunction(() => document.querySelector('#a').viewer.settings.exposure === 2,
                             null, { timeout: WAIT_MS });
    await pg.evaluate(() => window.frames(3));
    const bright = await shot(pg, '#a');
    assert.ok(mean(bright) > mean(dark) + 0.05,
              `exposure 4 (2 EV) brightens the image: mean ${mean(dark).toFixed(3)} -> ${mean(bright).toFixed(3)}`);
    const after = await pg.evaluate(() => ({ ...document.querySelector('#a').log,
                                             frame: document.querySelector('#a').viewer.state.frame }));
    assert.equal(after.converged, 1, 'exposure applies to the converged image: no new view');
    assert.equal(after.frame, 8);

    // A new camera is a new view: converged once more.
    await pg.evaluate(() => document.querySelector('#a').setAttribute('camera-orbit', '35deg 70deg auto'));
    log = await waitConverged(pg, '#a', 2);
    const turned = await shot(pg, '#a');
    assert.ok(meanDiff(turned, bright) > 0.02, `camera-orbit moves the view (${meanDiff(turned, bright).toFixed(4)})`);

    // src swap: the material grid replaces the Cornell box.
    await pg.evaluate((src) => { document.querySelector('#a').src = src; }, GRID);
    log = await waitConverged(pg, '#a', 3);
    assert.equal(log.load.length, 2);
    assert.match(log.load[1], /material_grid\.gltf$/);
    const grid = await shot(pg, '#a');
    assert.ok(meanDiff(grid, turned) > 0.05, `the new scene is shown (${meanDiff(grid, turned).toFixed(4)})`);
    await pg.waitForTimeout(1000);
    assert.equal((await pg.evaluate(() => document.querySelector('#a').log.converged)), 3,
                 'one converged event per view');
  });
});

test('a bad src or attribute fires error with a one-line message; the element goes on', { timeout: TEST_MS }, async () => {
  await withTestPage('errors', async (pg) => {
    await pg.evaluate(() => window.add(`<penumbra-viewer id="b" class="small" src="assets/missing.glb"
      frames="8"></penumbra-viewer>`));
    await pg.waitForFunction(() => document.querySelector('#b').log.error.length > 0, null, { timeout: WAIT_MS });
    let log = await pg.evaluate(() => document.querySelector('#b').log);
    assert.equal(log.error.length, 1);
    assert.equal(log.error[0].type, 'loadfailure');
    assert.match(log.error[0].message, /^cannot fetch http:\/\/127\.0\.0\.1:\d+\/assets\/missing\.glb: HTTP 404/);
    assert.doesNotMatch(log.error[0].message, /\n/);
    assert.deepEqual(log.load, []);

    // A bad setting value: named by its attribute, one line; the good ones apply.
    await pg.evaluate(() => {
      const el = document.querySelector('#b');
      el.setAttribute('fd', 'lots');
      el.setAttribute('occlusion-distance', '0.25');
    });
    await pg.waitForFunction(() => document.querySelector('#b').log.error.length > 1, null, { timeout: WAIT_MS });
    log = await pg.evaluate(() => document.querySelector('#b').log);
    assert.deepEqual(log.error[1], { type: 'attribute', message: 'fd="lots": not a number' });
    await pg.evaluate(() => document.querySelector('#b').setAttribute('frames', '0'));
    await pg.waitForFunction(() => document.querySelector('#b').log.error.length > 2, null, { timeout: WAIT_MS });
    log = await pg.evaluate(() => document.querySelector('#b').log);
    assert.equal(log.error[2].type, 'attribute');
    assert.match(log.error[2].message, /^frames="0": .*frames/);
    assert.doesNotMatch(log.error[2].message, /\n/);
    assert.equal(await pg.evaluate(() => document.querySelector('#b').viewer.settings.occlusionDistance), 0.25);

    // Still alive: a good src loads and converges (frames back to 8).
    await pg.evaluate((src) => {
      const el = document.querySelector('#b');
      el.setAttribute('frames', '8');
      el.removeAttribute('fd');
      el.src = src;
    }, CORNELL);
    await pg.waitForFunction(() => document.querySelector('#b').log.converged >= 1, null, { timeout: WAIT_MS });
    log = await pg.evaluate(() => document.querySelector('#b').log);
    assert.equal(log.error.length, 3, 'no further errors');
    assert.equal(log.load.length, 1);
    assert.equal(await pg.evaluate(() => document.querySelector('#b').loaded), true);
  });
});

test('loading="lazy" creates nothing off-screen; an eager element loads but draws nothing until seen', { timeout: TEST_MS }, async () => {
  await withTestPage('lazy', async (pg) => {
    await pg.evaluate((src) => {
      window.add('<div style="height: 3000px">spacer</div>');
      const row = window.add('<div id="row"></div>');
      window.add(`<penumbra-viewer id="lazy" class="small" loading="lazy" src="${src}" frames="8"></penumbra-viewer>`, row);
      window.add(`<penumbra-viewer id="eager" class="small" src="${src}" frames="8"></penumbra-viewer>`, row);
    }, CORNELL);
    await pg.waitForFunction(() => document.querySelector('#eager').log.load.length > 0 ||
                                   document.querySelector('#eager').log.error.length > 0,
                             null, { timeout: WAIT_MS });
    await pg.waitForTimeout(1500);  // time enough for frames, were any drawn
    const off = await pg.evaluate(() => {
      const lazy = document.querySelector('#lazy'), eager = document.querySelector('#eager');
      return { lazyViewer: lazy.viewer === null, lazyLog: lazy.log, eagerLog: eager.log,
               eagerFrame: eager.viewer.state.frame, eagerPaused: eager.viewer.state.paused };
    });
    assert.deepEqual(off.lazyLog, { load: [], error: [], converged: 0, progress: 0, camera: [],
                                   visibility: [], posterDismissed: 0, download: [] });
    assert.equal(off.lazyViewer, true, 'a lazy element off-screen has no viewer yet');
    assert.equal(off.eagerLog.load.length, 1, 'the eager element loaded its scene');
    assert.equal(off.eagerLog.progress, 0, 'and drew no frame off-screen');
    assert.equal(off.eagerFrame, 0);
    assert.equal(off.eagerPaused, true);

    await pg.evaluate(() => document.querySelector('#row').scrollIntoView());
    await waitConverged(pg, '#lazy', 1);
    await waitConverged(pg, '#eager', 1);
    const lazyShot = await shot(pg, '#lazy');
    assert.ok(mean(lazyShot) > 0.02, 'the lazy element shows the scene once on screen');
  });
});

test('sizes like an image, follows CSS; alt; camera-controls gates the orbit', { timeout: TEST_MS }, async () => {
  await withTestPage('size', async (pg) => {
    await pg.evaluate((src) => window.add(`<penumbra-viewer id="c" src="${src}" frames="8"
      adaptive-resolution="false" alt="Three boxes in a red and green room"></penumbra-viewer>`), CORNELL);
    let log = await waitConverged(pg, '#c', 1);
    const box = await pg.evaluate(() => {
      const el = document.querySelector('#c');
      const r = el.getBoundingClientRect();
      const c = el.shadowRoot.querySelector('canvas');
      return { w: r.width, h: r.height, display: getComputedStyle(el).display, cw: c.width,
               ch: c.height, role: el.getAttribute('role'), label: el.getAttribute('aria-label'),
               pointer: getComputedStyle(c).pointerEvents };
    });
    assert.deepEqual(box, { w: 300, h: 150, display: 'inline-block', cw: 300, ch: 150, role: 'img',
                            label: 'Three boxes in a red and green room', pointer: 'none' });

    // Without camera-controls a drag does nothing; with it, it orbits (a new view).
    const drag = async () => {
      const r = await pg.evaluate(() => {
        const b = document.querySelector('#c').getBoundingClientRect();
        return { x: b.x + b.width / 2, y: b.y + b.height / 2 };
      });
      await pg.mouse.move(r.x, r.y);
      await pg.mouse.down();
      for (let i = 1; i <= 5; i++) await pg.mouse.move(r.x + 8 * i, r.y + 2 * i);
      await pg.mouse.up();
    };
    await drag();
    await pg.waitForTimeout(1000);
    log = await pg.evaluate(() => document.querySelector('#c').log);
    assert.equal(log.converged, 1, 'no camera-controls: the drag changed nothing');
    await pg.evaluate(() => { document.querySelector('#c').cameraControls = true; });
    await pg.waitForFunction(() => getComputedStyle(document.querySelector('#c').shadowRoot
      .querySelector('canvas')).pointerEvents === 'auto', null, { timeout: WAIT_MS });
    await drag();
    await waitConverged(pg, '#c', 2);

    // CSS size: the canvas (and the drawing buffer) follow, also after convergence.
    await pg.evaluate(() => { document.querySelector('#c').style.cssText = 'width: 200px; height: 100px'; });
    await pg.waitForFunction(() => {
      const c = document.querySelector('#c').shadowRoot.querySelector('canvas');
      return c.width === 200 && c.height === 100;
    }, null, { timeout: WAIT_MS });
    await waitConverged(pg, '#c', 3);
  });
});

test('poster with reveal="interaction": nothing drawn until a click; removed and inserted again', { timeout: TEST_MS }, async () => {
  await withTestPage('poster', async (pg) => {
    await pg.evaluate((src) => window.add(`<penumbra-viewer id="p" class="small" src="${src}" frames="8"
      poster="assets/glass/lattice.png" reveal="interaction"></penumbra-viewer>`), CORNELL);
    await pg.waitForFunction(() => document.querySelector('#p').log.load.length > 0, null, { timeout: WAIT_MS });
    await pg.waitForTimeout(1500);
    const before = await pg.evaluate(() => {
      const el = document.querySelector('#p');
      const poster = el.shadowRoot.querySelector('.poster');
      return { progress: el.log.progress, posterHidden: poster.hidden, src: poster.getAttribute('src'),
               tabindex: el.getAttribute('tabindex') };
    });
    assert.deepEqual(before, { progress: 0, posterHidden: false, src: 'assets/glass/lattice.png', tabindex: '0' });
    await pg.click('#p');
    await waitConverged(pg, '#p', 1);
    assert.equal(await pg.evaluate(() => document.querySelector('#p').shadowRoot.querySelector('.poster').hidden), true);
    const shown = await pg.evaluate(() => ({ dismissed: document.querySelector('#p').log.posterDismissed,
                                             visibility: document.querySelector('#p').log.visibility }));
    assert.deepEqual(shown, { dismissed: 1, visibility: [true] }, 'poster-dismissed and model-visibility once each');

    // Removed, it frees its viewer and context; inserted again, it starts over on a new canvas.
    await pg.evaluate(() => { window.kept = document.querySelector('#p'); window.kept.remove(); });
    await pg.waitForFunction(() => window.kept.viewer === null, null, { timeout: WAIT_MS });
    await pg.evaluate(() => document.body.append(window.kept));
    await waitConverged(pg, '#p', 2);
    const again = await pg.evaluate(() => ({ loads: window.kept.log.load.length,
                                             canvases: window.kept.shadowRoot.querySelectorAll('canvas').length }));
    assert.deepEqual(again, { loads: 2, canvases: 1 });
  });
});

test('environment-image and the schema\'s settings as attributes; docs/web/api.md lists them', { timeout: TEST_MS }, async () => {
  await withTestPage('settings', async (pg) => {
    await pg.evaluate((src) => window.add(`<penumbra-viewer id="s" class="small" src="${src}" frames="8"
      environment-image="neutral" tone-mapping="neutral" occlusion-distance="0.3"
      screen-space-indirect="false"></penumbra-viewer>`), CORNELL);
    await waitConverged(pg, '#s', 1);
    let state = await pg.evaluate(() => {
      const v = document.querySelector('#s').viewer;
      return { env: v.info.scene.environment, s: v.settings };
    });
    assert.equal(state.env, 'studio', 'environment-image="neutral" is the built-in studio');
    assert.equal(state.s.toneMapper, 'pbr-neutral');
    assert.equal(state.s.occlusionDistance, 0.3);
    assert.equal(state.s.screenSpaceIndirect, false);
    const studio = await shot(pg, '#s');

    // A new environment restarts the view; wait for it to converge with that environment.
    const convergedWith = (env) => pg.waitForFunction((e) => {
      const el = document.querySelector('#s');
      return el.log.error.length > 0 ||
             (el.viewer.info.scene.environment === e && el.viewer.state.converged);
    }, env, { timeout: WAIT_MS, polling: 100 });
    await pg.evaluate(() => {
      const el = document.querySelector('#s');
      el.environmentImage = 'assets/env/studio_sky.hdr';
      el.removeAttribute('occlusion-distance');
    });
    await convergedWith('studio_sky.hdr');
    state = await pg.evaluate(() => {
      const el = document.querySelector('#s');
      const d = el.viewer.settingsSchema.find((e) => e.key === 'occlusionDistance').default;
      return { errors: el.log.error, od: el.viewer.settings.occlusionDistance, d };
    });
    assert.deepEqual(state.errors, []);
    assert.equal(state.od, state.d, 'a removed attribute sets the default back');
    assert.ok(meanDiff(await shot(pg, '#s'), studio) > 0.005, 'another environment, another image');
    // Removed: the rule for this scene (it has a light of its own: black).
    await pg.evaluate(() => document.querySelector('#s').removeAttribute('environment-image'));
    await convergedWith('none');

    // Every setting of the schema has its attribute in docs/web/api.md's table.
    const attrs = await pg.evaluate(() => document.querySelector('#s').viewer.settingsSchema
      .map((e) => window.settingAttribute(e.key)));
    const docs = readFileSync(join(root, 'docs/web/api.md'), 'utf8');
    const missing = attrs.filter((a) => !docs.includes(`| \`${a}\``));
    assert.deepEqual(missing, [], 'docs/web/api.md lists every settings attribute');
  });
});

test('variant-name selects a material variant, removing it restores the model\'s own, a bad one is an error', { timeout: TEST_MS }, async () => {
  await withTestPage('variants', async (pg) => {
    await pg.evaluate((src) => window.add(`<penumbra-viewer id="v" class="small" src="${src}" frames="8"
      variant-name="shifted"></penumbra-viewer>`), VARIANTS);
    await waitConverged(pg, '#v', 1);
    const scene = await pg.evaluate(() => document.querySelector('#v').viewer.info.scene);
    assert.deepEqual(scene.variants, ['shifted']);
    assert.equal(scene.variant, 'shifted');
    const shifted = await shot(pg, '#v');
    await pg.evaluate(() => document.querySelector('#v').removeAttribute('variant-name'));
    await waitConverged(pg, '#v', 2);
    assert.equal(await pg.evaluate(() => document.querySelector('#v').viewer.info.scene.variant), null);
    const own = await shot(pg, '#v');
    assert.ok(meanDiff(own, shifted) > 0.01, `the variant changes the image (${meanDiff(own, shifted).toFixed(4)})`);
    await pg.evaluate(() => document.querySelector('#v').setAttribute('variant-name', 'tartan'));
    await pg.waitForFunction(() => document.querySelector('#v').log.error.length > 0, null, { timeout: WAIT_MS });
    const error = (await pg.evaluate(() => document.querySelector('#v').log.error))[0];
    assert.equal(error.type, 'attribute');
    assert.match(error.message, /^variant-name="tartan": no variant 'tartan'/);
    assert.doesNotMatch(error.message, /\n/);
  });
});

test('auto-rotate turns the view once left alone and stops on a drag; model-viewer attributes Penumbra lacks warn once', { timeout: TEST_MS }, async () => {
  await withTestPage('autorotate', async (pg) => {
    const warnings = [];
    pg.on('console', (m) => { if (m.type() === 'warning') warnings.push(m.text()); });
    await pg.evaluate((src) => window.add(`<penumbra-viewer id="r" class="small" src="${src}" frames="8"
      adaptive-resolution="false" camera-controls auto-rotate auto-rotate-delay="0"
      rotation-per-second="90deg" ar shadow-softness="1"></penumbra-viewer>`), GRID);
    await pg.waitForFunction(() => document.querySelector('#r').loaded, null, { timeout: WAIT_MS });
    const yaw = () => pg.evaluate(() => {
      const c = document.querySelector('#r').viewer.camera;
      return Math.atan2(-c.forward[0], -c.forward[2]);
    });
    const a = await yaw();
    await pg.waitForTimeout(1500);
    const b = await yaw();
    const turned = Math.abs(Math.atan2(Math.sin(b - a), Math.cos(b - a)));
    assert.ok(turned > 0.3, `auto-rotate turns the view (${turned.toFixed(3)} rad in 1.5 s at 90deg/s)`);
    assert.equal(await pg.evaluate(() => document.querySelector('#r').log.converged), 0,
                 'a turning view does not converge');
    const sources = await pg.evaluate(() => document.querySelector('#r').log.camera);
    assert.ok(sources.includes('automatic'), `camera-change from auto-rotate: ${sources}`);
    assert.deepEqual(await pg.evaluate(() => document.querySelector('#r').log.visibility), [true],
                     'model-visibility once, visible');
    // A drag stops it; with a long delay it stays stopped and the view converges.
    await pg.evaluate(() => document.querySelector('#r').setAttribute('auto-rotate-delay', '600000'));
    const r = await pg.evaluate(() => {
      const x = document.querySelector('#r').getBoundingClientRect();
      return { x: x.x + x.width / 2, y: x.y + x.height / 2 };
    });
    await pg.mouse.move(r.x, r.y);
    await pg.mouse.down();
    await pg.mouse.move(r.x + 4, r.y);
    await pg.mouse.up();
    await waitConverged(pg, '#r', 1);
    const after = await pg.evaluate(() => document.querySelector('#r').log.camera);
    assert.ok(after.includes('user-interaction'), `camera-change from the drag: ${after}`);
    const c = await yaw();
    await pg.waitForTimeout(1000);
    const d = await yaw();
    assert.ok(Math.abs(d - c) < 1e-6, `stopped after the drag (${Math.abs(d - c)})`);
    // Removing auto-rotate: the element converges and the loop sleeps.
    await pg.evaluate(() => document.querySelector('#r').removeAttribute('auto-rotate'));
    // One warning each for ar and shadow-softness, however many passes ran.
    await pg.evaluate(() => document.querySelector('#r').setAttribute('exposure', '1'));
    await pg.waitForTimeout(500);
    const mine = warnings.filter((w) => /is model-viewer's and not supported/.test(w));
    assert.equal(mine.filter((w) => w.includes('[penumbra-viewer] ar is')).length, 1, mine.join('\n'));
    assert.equal(mine.filter((w) => w.includes('shadow-softness')).length, 1, mine.join('\n'));
    assert.equal(mine.length, 2, mine.join('\n'));
  });
});

test('progress is the download\'s, as model-viewer\'s: 0 first, never back, 1 before load; the bar and its slot', { timeout: TEST_MS }, async () => {
  await withTestPage('download', async (pg) => {
    await pg.evaluate((src) => window.add(`<penumbra-viewer id="d" class="small" src="${src}" frames="4"
      adaptive-resolution="false"></penumbra-viewer>`), GRID);
    const log = await waitConverged(pg, '#d', 1);
    const events = log.download;
    assert.equal(events[0], 0, `the download begins at 0: ${JSON.stringify(events)}`);
    const load = events.indexOf('load');
    assert.ok(load > 1 && events[load - 1] === 1, `1 comes before load: ${JSON.stringify(events)}`);
    const values = events.slice(0, load);
    for (let i = 1; i < values.length; ++i) {
      assert.ok(values[i] >= values[i - 1], `never going back: ${JSON.stringify(values)}`);
    }
    assert.ok(log.progress >= 4, 'the refinement has its own event (refine-progress)');
    const bar = await pg.evaluate(() => {
      const b = document.querySelector('#d').shadowRoot.querySelector('[part="default-progress-bar"]');
      return { hidden: b.hidden, width: b.firstElementChild.style.width };
    });
    assert.deepEqual(bar, { hidden: true, width: '100%' }, 'the default bar is full and gone once loaded');
    // A page's own bar in slot "progress-bar" replaces the default one.
    const slotted = await pg.evaluate((src) => {
      const el = window.add(`<penumbra-viewer class="small" src="${src}"><div slot="progress-bar"
        id="mine"></div></penumbra-viewer>`);
      const slot = el.shadowRoot.querySelector('slot[name="progress-bar"]');
      return slot.assignedElements().map((e) => e.id);
    }, GRID);
    assert.deepEqual(slotted, ['mine']);
  });
});


test('skybox-image changes the background and not the lighting; alone it lights too, as model-viewer\'s', { timeout: TEST_MS }, async () => {
  await withTestPage('skybox', async (pg) => {
    const common = `class="small" src="${GRID}" frames="4" adaptive-resolution="false"`;
    await pg.evaluate((c) => {
      window.add(`<penumbra-viewer id="env" ${c} environment-image="assets/env/studio_sky.hdr"></penumbra-viewer>`);
      window.add(`<penumbra-viewer id="both" ${c} environment-image="assets/env/studio_sky.hdr"
        skybox-image="assets/env/studio.hdr"></penumbra-viewer>`);
      window.add(`<penumbra-viewer id="sky" ${c} skybox-image="assets/env/studio.hdr"></penumbra-viewer>`);
    }, common);
    for (const id of ['#env', '#both', '#sky']) await waitConverged(pg, id, 1);
    const [env, both, sky] = [await shot(pg, '#env'), await shot(pg, '#both'), await shot(pg, '#sky')];
    // Mean |difference| over rows [y0, y1) and columns [x0, x1), in [0, 1].
    const region = (a, b, x0, x1, y0, y1) => {
      let sum = 0, n = 0;
      for (let y = y0; y < y1; y++) {
        for (let x = x0; x < x1; x++) {
          const i = (y * a.width + x) * 4;
          for (let c = 0; c < 3; c++, n++) sum += Math.abs(a.data[i + c] - b.data[i + c]);
        }
      }
      return sum / n / 255;
    };
    const { width: w, height: h } = env;
    const skyBand = (a, b) => region(a, b, 0, w, 0, Math.round(h * 0.08));
    const centre = (a, b) => region(a, b, w / 2 - 2, w / 2 + 2, h / 2 - 2, h / 2 + 2);
    const figures = { backgroundChange: skyBand(env, both), litChange: centre(env, both),
                      aloneLit: centre(env, sky), aloneBackground: skyBand(both, sky) };
    console.log(`# skybox: ${JSON.stringify(figures)}`);
    assert.ok(figures.backgroundChange > 0.03, `the skybox is the background: ${JSON.stringify(figures)}`);
    assert.ok(figures.litChange < 0.01, `and lights nothing: ${JSON.stringify(figures)}`);
    assert.ok(figures.aloneLit > 0.01, `alone it lights the model: ${JSON.stringify(figures)}`);
    assert.ok(figures.aloneBackground < 0.01, `and is its background: ${JSON.stringify(figures)}`);
    // Removed: the environment is the background again.
    await pg.evaluate(() => document.querySelector('#both').removeAttribute('skybox-image'));
    await waitConverged(pg, '#both', 2);
    const restored = await shot(pg, '#both');
    assert.ok(skyBand(env, restored) < 0.01, 'removing skybox-image shows the environment again');
  });
});

test('transparent-background: the page (a CSS colour here) shows where the model is not, as model-viewer\'s canvas', { timeout: TEST_MS }, async () => {
  await withTestPage('transparent', async (pg) => {
    const common = `class="small" src="${GRID}" frames="4" adaptive-resolution="false"
      environment-image="assets/env/studio_sky.hdr" style="background: rgb(255, 0, 255)"`;
    await pg.evaluate((c) => {
      window.add(`<penumbra-viewer id="clear" ${c} transparent-background></penumbra-viewer>`);
      window.add(`<penumbra-viewer id="drawn" ${c}></penumbra-viewer>`);
    }, common);
    for (const id of ['#clear', '#drawn']) await waitConverged(pg, id, 1);
    const [clear, drawn] = [await onPage(pg, '#clear'), await onPage(pg, '#drawn')];
    // The share of magenta pixels in the top fifth (the sky above the grid) and at the centre.
    const magenta = (img, y0, y1, x0 = 0, x1 = img.width) => {
      let n = 0, m = 0;
      for (let y = y0; y < y1; y++) {
        for (let x = x0; x < x1; x++, n++) {
          const i = (y * img.width + x) * 4;
          if (img.data[i] > 235 && img.data[i + 1] < 25 && img.data[i + 2] > 235) m++;
        }
      }
      return m / n;
    };
    const h = clear.height, w = clear.width;
    const figures = { clearTop: magenta(clear, 0, Math.round(h / 5)), drawnTop: magenta(drawn, 0, Math.round(h / 5)),
                      clearCentre: magenta(clear, h / 2 - 3, h / 2 + 3, w / 2 - 3, w / 2 + 3) };
    console.log(`# transparent: ${JSON.stringify(figures)}`);
    assert.ok(figures.clearTop > 0.6, `the page shows through above the model: ${JSON.stringify(figures)}`);
    assert.equal(figures.drawnTop, 0, `without the attribute the environment is drawn: ${JSON.stringify(figures)}`);
    assert.equal(figures.clearCentre, 0, `the model covers the page: ${JSON.stringify(figures)}`);
    // The canvas itself: alpha 0 in the corner, 255 at the centre.
    const canvas = await shot(pg, '#clear');
    const alpha = (x, y) => canvas.data[(y * canvas.width + x) * 4 + 3];
    assert.equal(alpha(1, 1), 0, 'a transparent corner');
    assert.equal(alpha(canvas.width >> 1, canvas.height >> 1), 255, 'an opaque model');
  });
});

test('shadow-intensity darkens the ground under the model and not the sky, converging; over the page with transparent-background', { timeout: TEST_MS }, async () => {
  await withTestPage('ground-shadow', async (pg) => {
    const common = `class="small" src="${FLOATING}" frames="8" adaptive-resolution="false"
      camera-orbit="0deg 60deg auto" environment-image="assets/env/studio_sky.hdr"
      transparent-background style="background: rgb(255, 255, 255)"`;
    await pg.evaluate((c) => {
      window.add(`<penumbra-viewer id="shadow" ${c} shadow-intensity="1"></penumbra-viewer>`);
      window.add(`<penumbra-viewer id="none" ${c}></penumbra-viewer>`);
    }, common);
    for (const id of ['#shadow', '#none']) await waitConverged(pg, id, 1);
    const [shadow, none] = [await onPage(pg, '#shadow'), await onPage(pg, '#none')];
    // The mean brightness (0-255) of rows [y0, y1) across the middle half of the element.
    const mean = (img, y0, y1) => {
      let sum = 0, n = 0;
      for (let y = Math.round(y0); y < Math.round(y1); y++) {
        for (let x = Math.round(img.width / 4); x < Math.round(img.width * 3 / 4); x++, n++) {
          const i = (y * img.width + x) * 4;
          sum += (img.data[i] + img.data[i + 1] + img.data[i + 2]) / 3;
        }
      }
      return sum / n;
    };
    const h = shadow.height;
    // In front of the spheres' lowest row, seen from above (the bottom of the element).
    const figures = { groundShadow: mean(shadow, h * 0.86, h), groundNone: mean(none, h * 0.86, h),
                      skyShadow: mean(shadow, 0, h * 0.08), skyNone: mean(none, 0, h * 0.08) };
    console.log(`# ground shadow: ${JSON.stringify(figures)}`);
    assert.ok(figures.groundNone > 250, `without it the page shows under the model: ${JSON.stringify(figures)}`);
    assert.ok(figures.groundShadow < figures.groundNone - 8, `the ground under the model darkens: ${JSON.stringify(figures)}`);
    assert.ok(Math.abs(figures.skyShadow - figures.skyNone) < 0.5, `the sky above is untouched: ${JSON.stringify(figures)}`);
  });
});

test('interaction-prompt: a hand after the threshold with camera-controls, gone at the first touch; none and no controls: never', { timeout: TEST_MS }, async () => {
  await withTestPage('prompt', async (pg) => {
    const common = `class="small" src="${CORNELL}" frames="4" adaptive-resolution="false" interaction-prompt-threshold="300"`;
    await pg.evaluate((c) => {
      window.add(`<penumbra-viewer id="p" ${c} camera-controls></penumbra-viewer>`);
      window.add(`<penumbra-viewer id="none" ${c} camera-controls interaction-prompt="none"></penumbra-viewer>`);
      window.add(`<penumbra-viewer id="still" ${c}></penumbra-viewer>`);
    }, common);
    for (const id of ['#p', '#none', '#still']) await waitConverged(pg, id, 1);
    await pg.waitForTimeout(600);
    const shown = () => pg.evaluate(() => Object.fromEntries(['p', 'none', 'still'].map((id) => [
      id, !document.querySelector(`#${id}`).shadowRoot.querySelector('.prompt').hidden])));
    assert.deepEqual(await shown(), { p: true, none: false, still: false });
    const style = await pg.evaluate(() =>
      document.querySelector('#p').shadowRoot.querySelector('.prompt').classList.contains('wiggle'));
    assert.equal(style, true, 'wiggle is the default style');
    await pg.evaluate(() => document.querySelector('#p').dispatchEvent(
      new PointerEvent('pointerdown', { bubbles: true })));
    await pg.waitForTimeout(600);
    assert.deepEqual(await shown(), { p: false, none: false, still: false }, 'the first touch takes it away');
  });
});
