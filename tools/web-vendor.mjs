#!/usr/bin/env node
// Copies the path tracer of the hand-off page (three.js, three-gpu-pathtracer, three-mesh-bvh)
// from web/node_modules into a folder of web/dist: only the ES module files reachable by static
// imports from the page's entry points, under <out>/<package>/<path>, so the page's import map
// (web/handoff/index.html) finds them. Nothing is fetched: web/node_modules comes from
// web/package-lock.json (tools/setup runs `npm ci`). Prints the bytes per package.
//   node tools/web-vendor.mjs --out web/dist/handoff/vendor
import { copyFileSync, existsSync, mkdirSync, readFileSync, rmSync } from 'node:fs';
import { dirname, join, relative, resolve } from 'node:path';
import { gzipSync } from 'node:zlib';
import { fileURLToPath } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const nm = join(root, 'web/node_modules');
const args = process.argv.slice(2);
const outArg = args.indexOf('--out');
const out = resolve(outArg >= 0 ? args[outArg + 1] : join(root, 'web/dist/handoff/vendor'));

// Bare specifiers: the same mapping as the page's import map.
const BARE = [
  ['three/examples/jsm/', (s) => join(nm, 'three/examples/jsm', s.slice('three/examples/jsm/'.length))],
  ['three-mesh-bvh', () => join(nm, 'three-mesh-bvh/src/index.js')],
  ['three-gpu-pathtracer', () => join(nm, 'three-gpu-pathtracer/src/index.js')],
  ['three', () => join(nm, 'three/build/three.module.js')],
];
const ENTRIES = ['three', 'three/examples/jsm/loaders/GLTFLoader.js',
                 'three/examples/jsm/loaders/HDRLoader.js', 'three-gpu-pathtracer'];

function resolveSpec(spec, from) {
  if (spec.startsWith('.')) return resolve(dirname(from), spec);
  for (const [prefix, map] of BARE) {
    if (spec === prefix || (prefix.endsWith('/') && spec.startsWith(prefix))) return map(spec);
  }
  return null;
}

// Static imports and re-exports (`import x from '...'`, `export * from '...'`, `import '...'`).
const IMPORT = /(?:^|[;\n}])\s*(?:import|export)\s*(?:[\w*{}\s,$]*?\sfrom\s*)?['"]([^'"\n]+)['"]/g;

const seen = new Set();
const unresolved = new Set();
const queue = ENTRIES.map((e) => resolveSpec(e, root));
while (queue.length) {
  const file = queue.pop();
  if (seen.has(file)) continue;
  if (!existsSync(file)) {
    console.error(`web-vendor: ${relative(root, file)} is missing: run tools/setup (npm ci in web/)`);
    process.exit(1);
  }
  seen.add(file);
  const text = readFileSync(file, 'utf8');
  for (const m of text.matchAll(IMPORT)) {
    const target = resolveSpec(m[1], file);
    if (target) queue.push(target);
    else unresolved.add(`${m[1]} (from ${relative(nm, file)})`);
  }
}
if (unresolved.size) {
  console.error(`web-vendor: unresolved imports: ${[...unresolved].join(', ')}`);
  process.exit(1);
}

rmSync(out, { recursive: true, force: true });
const sizes = new Map();
for (const file of [...seen].sort()) {
  const rel = relative(nm, file);
  mkdirSync(dirname(join(out, rel)), { recursive: true });
  copyFileSync(file, join(out, rel));
  const pkg = rel.split('/')[0];
  const bytes = readFileSync(file);
  const s = sizes.get(pkg) || { files: 0, bytes: 0, parts: [] };
  s.files++;
  s.bytes += bytes.length;
  s.parts.push(bytes);
  sizes.set(pkg, s);
}
const line = [...sizes].map(([pkg, s]) => {
  const gz = gzipSync(Buffer.concat(s.parts), { level: 9 }).length;
  const version = JSON.parse(readFileSync(join(nm, pkg, 'package.json'), 'utf8')).version;
  return `${pkg} ${version}: ${s.files} files ${s.bytes} B (gzip -9: ${gz} B)`;
});
console.log(`web-vendor: ${relative(root, out)} (hand-off page only): ${line.join(', ')}`);
