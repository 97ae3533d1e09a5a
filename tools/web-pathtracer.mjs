#!/usr/bin/env node
// Bundles the hand-off page's path-tracer worker (web/handoff/worker.mjs with pathtracer.mjs,
// three.js, three-gpu-pathtracer and three-mesh-bvh from web/node_modules) into one ES module,
// <out>/pathtracer-worker.js, with esbuild (pinned in web/package-lock.json, installed by
// tools/setup; nothing is fetched). One file because a module worker gets no import map. Prints
// the bytes each package adds.
//   node tools/web-pathtracer.mjs --out web/dist/handoff
import { mkdirSync, readFileSync } from 'node:fs';
import { dirname, join, relative, resolve } from 'node:path';
import { gzipSync } from 'node:zlib';
import { fileURLToPath } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const web = join(root, 'web');
const args = process.argv.slice(2);
const outArg = args.indexOf('--out');
const out = resolve(outArg >= 0 ? args[outArg + 1] : join(web, 'dist/handoff'));

let esbuild;
try {
  esbuild = await import(join(web, 'node_modules/esbuild/lib/main.js'));
} catch (e) {
  console.error(`web-pathtracer: esbuild is missing from web/node_modules: run tools/setup (npm ci in web/) (${e.message})`);
  process.exit(1);
}
mkdirSync(out, { recursive: true });
const file = join(out, 'pathtracer-worker.js');
let result;
try {
  result = await esbuild.build({
    absWorkingDir: web, entryPoints: ['handoff/worker.mjs'], bundle: true, format: 'esm',
    target: 'es2022', minify: true, legalComments: 'eof', outfile: file, metafile: true, logLevel: 'silent',
  });
} catch (e) {
  console.error(`web-pathtracer: ${e.message.split('\n')[0]}`);
  process.exit(1);
}
// Bytes in the bundle per package (the page's own files under "handoff").
const perPackage = new Map();
for (const [input, { bytesInOutput }] of Object.entries(result.metafile.outputs[Object.keys(result.metafile.outputs)[0]].inputs)) {
  const m = input.match(/node_modules\/((?:@[^/]+\/)?[^/]+)/);
  const pkg = m ? m[1] : 'handoff';
  perPackage.set(pkg, (perPackage.get(pkg) || 0) + bytesInOutput);
}
const versions = [...perPackage].map(([pkg, bytes]) => {
  const v = pkg === 'handoff' ? '' : ` ${JSON.parse(readFileSync(join(web, 'node_modules', pkg, 'package.json'), 'utf8')).version}`;
  return `${pkg}${v} ${bytes} B`;
});
const bytes = readFileSync(file);
console.log(`web-pathtracer: ${relative(root, file)} (hand-off page only): ${bytes.length} B ` +
            `(gzip -9: ${gzipSync(bytes, { level: 9 }).length} B; ${versions.join(', ')})`);
