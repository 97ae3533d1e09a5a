// The npm package (web/dist/penumbra-viewer.tgz, made by tools/build-web with `npm pack`) as a
// user gets it: installed offline into an empty folder, its package.json (version from
// CMakeLists.txt, exports, types), then <penumbra-viewer> on a plain HTML page that reaches the
// package through an import map, and on a page bundled by esbuild (from web/node_modules,
// pinned by web/package-lock.json). Both must show the model: pixels that are not blank and
// differ from the background around it. The plain page loads a meshopt-compressed model and
// the bundled one a Draco-compressed one, so the decoders must be found relative to the
// modules (new URL(..., import.meta.url)) in both cases. Screenshots go to
// build-web/test-output/package-{plain,bundled}.png. No bound on response times.
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { copyFileSync, cpSync, existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync,
         rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import * as esbuild from 'esbuild';
import { closeServer, dist, launch, outDir, recordConsole, root, serve,
         withTimeout } from './harness.mjs';

const TARBALL = join(dist, 'penumbra-viewer.tgz');
const WAIT_MS = 120_000;
const TEST_MS = 240_000;

let work, pkgDir, manifest, browser;
const consoleLines = [];

before(async () => {
  if (!existsSync(TARBALL)) throw new Error(`${TARBALL} is missing: run tools/build-web first`);
  mkdirSync(outDir, { recursive: true });
  work = mkdtempSync(join(tmpdir(), 'penumbra-package-'));
  writeFileSync(join(work, 'package.json'), '{ "name": "penumbra-package-test", "private": true }\n');
  // Offline, with an empty cache of its own: the package has no dependencies, so nothing may
  // need the registry.
  const r = spawnSync('npm', ['install', '--offline', '--no-audit', '--no-fund', '--ignore-scripts',
                              '--loglevel=error', TARBALL],
                      { cwd: work, encoding: 'utf8', timeout: 120_000,
                        env: { ...process.env, npm_config_cache: join(work, '.npm-cache'),
                               npm_config_update_notifier: 'false' } });
  assert.equal(r.status, 0, `npm install ${TARBALL} failed: ${r.stderr}${r.error || ''}`);
  pkgDir = join(work, 'node_modules/penumbra-viewer');
  manifest = JSON.parse(readFileSync(join(pkgDir, 'package.json'), 'utf8'));
  browser = await launch({ viewport: { width: 320, height: 240 } });
}, { timeout: 180_000 });

after(async () => {
  if (browser) await browser.close();
  if (work) rmSync(work, { recursive: true, force: true });
});

test('package.json: the project\'s version, exports and types that exist, the core and decoders', () => {
  const cmake = readFileSync(join(root, 'CMakeLists.txt'), 'utf8');
  const version = /project\(penumbra\s+VERSION\s+([\d.]+)/.exec(cmake)?.[1];
  assert.ok(version, 'CMakeLists.txt has project(penumbra VERSION x.y.z)');
  assert.equal(manifest.name, 'penumbra-viewer');
  assert.equal(manifest.version, version);
  assert.equal(manifest.type, 'module');
  assert.deepEqual(manifest.dependencies ?? {}, {}, 'no dependencies: installs offline');
  for (const [sub, entry] of Object.entries(manifest.exports)) {
    for (const target of typeof entry === 'string' ? [entry] : Object.values(entry)) {
      assert.ok(existsSync(join(pkgDir, target)), `exports["${sub}"] -> ${target} exists`);
    }
  }
  assert.equal(manifest.exports['.'].types, './element.d.ts');
  assert.equal(manifest.exports['./api'].types, './penumbra.d.ts');
  const dts = readFileSync(join(pkgDir, 'element.d.ts'), 'utf8');
  assert.match(dts, /'penumbra-viewer': PenumbraViewerElement/);
  for (const f of ['penumbra_viewer.js', 'penumbra_viewer.wasm', 'version.mjs',
                   'decoders/meshopt_decoder.mjs', 'decoders/draco_decoder_gltf.wasm',
                   'decoders/basis_transcoder.wasm']) {
    assert.ok(existsSync(join(pkgDir, f)), `${f} is in the package`);
  }
  assert.match(readFileSync(join(pkgDir, 'version.mjs'), 'utf8'), new RegExp(`'${version.replace(/\./g, '\\.')}'`));
});

// Serves `dir`, opens `page`, waits for the element to converge; returns what the page saw and
// the URLs it fetched.
async function render(dir, name) {
  const server = await serve(dir);
  const pg = await withTimeout(browser.context.newPage(), 10_000, 'new page');
  recordConsole(pg, consoleLines);
  const requests = [];
  pg.on('request', (r) => requests.push(new URL(r.url()).pathname));
  try {
    await pg.goto(`http://127.0.0.1:${server.address().port}/index.html`, { timeout: 20_000 });
    await pg.waitForFunction(() => window.result && (window.result.converged || window.result.error),
                             null, { timeout: WAIT_MS, polling: 100 });
    const result = await pg.evaluate(() => {
      const el = document.querySelector('penumbra-viewer');
      const c = el.shadowRoot.querySelector('canvas');
      const t = document.createElement('canvas');
      t.width = c.width;
      t.height = c.height;
      const ctx = t.getContext('2d');
      ctx.drawImage(c, 0, 0);
      return { ...window.result, width: t.width, height: t.height,
               data: [...ctx.getImageData(0, 0, t.width, t.height).data] };
    });
    await withTimeout(pg.screenshot({ path: join(outDir, `package-${name}.png`), timeout: 8_000 }),
                      10_000, 'screenshot').catch(() => {});
    return { result, requests };
  } catch (e) {
    e.message += `\n--- console ---\n${consoleLines.slice(-30).join('\n')}`;
    throw e;
  } finally {
    await withTimeout(pg.close(), 10_000, 'close page').catch(() => {});
    closeServer(server);
  }
}

// The model is framed in the middle: the middle of the image must differ from its border (the
// background), and the image must not be blank.
function assertShowsModel(img) {
  assert.equal(img.error, undefined, `no error: ${img.error}`);
  assert.ok(img.width >= 100 && img.height >= 75, `canvas ${img.width}x${img.height}`);
  const region = (inside) => {
    let sum = [0, 0, 0], n = 0;
    for (let y = 0; y < img.height; y++) {
      for (let x = 0; x < img.width; x++) {
        const u = x / img.width, v = y / img.height;
        const centre = Math.abs(u - 0.5) < 0.15 && Math.abs(v - 0.5) < 0.15;
        const border = u < 0.08 || u > 0.92 || v < 0.08 || v > 0.92;
        if (inside ? !centre : !border) continue;
        for (let c = 0; c < 3; c++) sum[c] += img.data[(y * img.width + x) * 4 + c] / 255;
        n++;
      }
    }
    return sum.map((s) => s / n);
  };
  const centre = region(true), border = region(false);
  const lum = (c) => 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
  assert.ok(Math.max(lum(centre), lum(border)) > 0.05, `not blank (centre ${lum(centre)}, border ${lum(border)})`);
  const d = Math.max(...centre.map((c, i) => Math.abs(c - border[i])));
  assert.ok(d > 0.04, `the model differs from the background: centre [${centre.map((c) => c.toFixed(3))}] ` +
                      `vs border [${border.map((c) => c.toFixed(3))}]`);
}

const PAGE_SCRIPT = `
  const el = document.querySelector('penumbra-viewer');
  el.addEventListener('converged', () => { window.result = { ...window.result, converged: true }; });
  el.addEventListener('error', (e) => { window.result = { error: e.detail.message }; });
  el.addEventListener('load', () => { window.result = { ...window.result, version: Penumbra.version }; });
  window.result = {};`;
const ELEMENT = '<penumbra-viewer src="model.glb" environment-image="studio.hdr" exposure="1" ' +
                'frames="8" style="width: 200px; height: 150px"></penumbra-viewer>';

test('a plain page with an import map to the installed package shows the model', { timeout: TEST_MS }, async () => {
  // The folder the package was installed into, served as it is.
  const site = work;
  copyFileSync(join(dist, 'assets/compressed/product_meshopt.glb'), join(site, 'model.glb'));
  copyFileSync(join(dist, 'assets/env/studio_sky.hdr'), join(site, 'studio.hdr'));
  const entry = `./node_modules/penumbra-viewer/${manifest.exports['.'].default.replace(/^\.\//, '')}`;
  writeFileSync(join(site, 'index.html'), `<!doctype html><meta charset="utf-8">
<script type="importmap">${JSON.stringify({ imports: { 'penumbra-viewer': entry } })}</script>
${ELEMENT}
<script type="module">
  import { Penumbra } from 'penumbra-viewer';
  ${PAGE_SCRIPT}
</script>`);
  const { result, requests } = await render(site, 'plain');
  assertShowsModel(result);
  assert.equal(result.version, manifest.version, 'Penumbra.version is the package\'s');
  assert.ok(requests.includes('/node_modules/penumbra-viewer/penumbra_viewer.wasm'), 'the core next to the module');
  assert.ok(requests.includes('/node_modules/penumbra-viewer/decoders/meshopt_decoder.mjs'),
            `the meshopt decoder from the package's decoders/: ${requests.join(' ')}`);
  assert.ok(!requests.some((p) => p.includes('draco') || p.includes('basis')), 'no decoder the model does not need');
});

test('a page bundled by esbuild (ESM, no configuration) shows the model', { timeout: TEST_MS }, async () => {
  const app = join(work, 'app');
  const out = join(app, 'out');
  mkdirSync(app);
  writeFileSync(join(app, 'main.mjs'), `import { Penumbra } from 'penumbra-viewer';\n${PAGE_SCRIPT}\n`);
  // 'penumbra-viewer' resolves to the installed package (work/node_modules), as in a project.
  const built = await esbuild.build({ absWorkingDir: app, entryPoints: ['main.mjs'], bundle: true,
                                      format: 'esm', outdir: 'out', logLevel: 'silent' });
  assert.deepEqual(built.errors, []);
  assert.deepEqual(built.warnings.map((w) => w.text), []);
  assert.deepEqual(readdirSync(out), ['main.js'], 'one bundle');
  // esbuild leaves new URL(..., import.meta.url) as it is: the wasm and the decoders go next to
  // the bundle (docs/web/api.md, "The npm package").
  copyFileSync(join(pkgDir, 'penumbra_viewer.wasm'), join(out, 'penumbra_viewer.wasm'));
  cpSync(join(pkgDir, 'decoders'), join(out, 'decoders'), { recursive: true });
  copyFileSync(join(dist, 'assets/compressed/product_draco.glb'), join(out, 'model.glb'));
  copyFileSync(join(dist, 'assets/env/studio_sky.hdr'), join(out, 'studio.hdr'));
  writeFileSync(join(out, 'index.html'), `<!doctype html><meta charset="utf-8">
${ELEMENT}
<script type="module" src="main.js"></script>`);
  const { result, requests } = await render(out, 'bundled');
  assertShowsModel(result);
  assert.equal(result.version, manifest.version);
  assert.ok(requests.includes('/penumbra_viewer.wasm'), 'the core next to the bundle');
  assert.ok(requests.includes('/decoders/draco_decoder_gltf.wasm'),
            `the Draco decoder from decoders/ next to the bundle: ${requests.join(' ')}`);
  assert.ok(!requests.some((p) => /\/(element|penumbra|loop|adapt|orbit|staging|decoders|wasm_api|version)\.mjs$|penumbra_viewer\.js$/.test(p)),
            `the package's modules are in the bundle: ${requests.join(' ')}`);
});
