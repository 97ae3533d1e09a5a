#!/usr/bin/env node
// Makes the npm package penumbra-viewer from a built web/dist/lib (tools/build-web runs it):
// the element (element.mjs, the entry), the JS API and its helpers, their .d.ts files, the wasm
// core (penumbra_viewer.js + .wasm) and decoders/ (fetched only when a file needs them, by URLs
// relative to the modules, so the package works unbundled and bundled alike). package.json is
// web/package/package.json with the version of version.mjs, which CMake writes from the
// project's version. `npm pack` (no network: the package has no dependencies) writes the
// tarball. Prints what went in and the sizes.
//   node tools/web-package.mjs --lib web/dist/lib --work build-web/npm-package \
//     --out web/dist/penumbra-viewer.tgz
import { execFileSync } from 'node:child_process';
import { copyFileSync, cpSync, existsSync, mkdirSync, readdirSync, readFileSync, renameSync,
         rmSync, statSync, writeFileSync } from 'node:fs';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { gzipSync } from 'node:zlib';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const args = process.argv.slice(2);
const arg = (name, fallback) => {
  const i = args.indexOf(name);
  return resolve(i >= 0 && args[i + 1] ? args[i + 1] : fallback);
};
const lib = arg('--lib', join(root, 'web/dist/lib'));
const work = arg('--work', join(root, 'build-web/npm-package'));
const out = arg('--out', join(root, 'web/dist/penumbra-viewer.tgz'));
const fail = (message) => {
  console.error(`web-package: ${message}`);
  process.exit(1);
};

// What the package holds from lib/: every module, its types, the core and the decoders.
const wanted = (name) => /\.(mjs|d\.ts)$/.test(name) || /^penumbra_viewer\.(js|wasm)$/.test(name);
const files = readdirSync(lib).filter(wanted);
for (const need of ['element.mjs', 'penumbra.mjs', 'version.mjs', 'penumbra_viewer.wasm']) {
  if (!files.includes(need)) fail(`${relative(root, join(lib, need))} is missing: run tools/build-web`);
}
if (!existsSync(join(lib, 'decoders'))) fail(`${relative(root, lib)}/decoders is missing`);

const { version } = await import(pathToFileURL(join(lib, 'version.mjs')).href);
if (!/^\d+\.\d+\.\d+/.test(version)) fail(`version.mjs says '${version}', not a version`);
const template = JSON.parse(readFileSync(join(root, 'web/package/package.json'), 'utf8'));
const { name, ...rest } = template;
const manifest = { name, version, ...rest };

rmSync(work, { recursive: true, force: true });
mkdirSync(work, { recursive: true });
for (const f of files) copyFileSync(join(lib, f), join(work, f));
cpSync(join(lib, 'decoders'), join(work, 'decoders'), { recursive: true });
copyFileSync(join(root, 'web/package/README.md'), join(work, 'README.md'));
writeFileSync(join(work, 'package.json'), `${JSON.stringify(manifest, null, 2)}\n`);
// Every target of "exports" must be in the package.
for (const entry of Object.values(manifest.exports)) {
  for (const target of typeof entry === 'string' ? [entry] : Object.values(entry)) {
    if (!existsSync(join(work, target))) fail(`exports names ${target}, which is not in the package`);
  }
}

// npm pack: the tarball as the registry would get it; offline, no scripts, no notices.
const env = { ...process.env, npm_config_update_notifier: 'false', npm_config_fund: 'false',
              npm_config_audit: 'false', npm_config_offline: 'true' };
const packed = JSON.parse(execFileSync('npm', ['pack', '--json', '--ignore-scripts',
                                               '--pack-destination', work],
                                       { cwd: work, env, encoding: 'utf8' }));
mkdirSync(dirname(out), { recursive: true });
renameSync(join(work, packed[0].filename), out);

const size = (f) => statSync(join(lib, f)).size;
const gz = (...fs) => gzipSync(Buffer.concat(fs.map((f) => readFileSync(join(lib, f)))), { level: 9 }).length;
const api = files.filter((f) => f.endsWith('.mjs') && f !== 'element.mjs');
const apiBytes = api.reduce((s, f) => s + size(f), 0);
console.log(`web-package: ${relative(root, out)}: ${manifest.name}@${version}, ` +
            `${packed[0].entryCount} files, ${statSync(out).size} B (unpacked ${packed[0].unpackedSize} B)`);
console.log(`web-package: element.mjs ${size('element.mjs')} B (gzip -9: ${gz('element.mjs')} B); ` +
            `JS API ${api.join(' ')} ${apiBytes} B (gzip -9: ${gz(...api)} B); core ` +
            `penumbra_viewer.js + .wasm ${size('penumbra_viewer.js') + size('penumbra_viewer.wasm')} B`);
