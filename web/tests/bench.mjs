// Benchmark (prints only; not part of tools/test-web): milliseconds per intermediate frame of
// the Cornell box in headless Chromium (WebGL2 on SwiftShader) next to the native figure from
// penumbra-render at the same size and frame count, plus the size of the viewer's wasm + JS.
//
//   node web/tests/bench.mjs [--size 256] [--frames 32]
//
// Browser: Viewer.benchmark() after one full accumulation at that size (so every shader has
// compiled): `frames` steps back to back with one 1-pixel read-back at the end (throughput),
// and the same with a read-back after every step (what the frame loop's time budget sees).
// Native: penumbra-render --frames N, its printed wall time divided by N (its clock starts after
// the context, renderer and programs exist, and stops after the last step, without a finish).
import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { gzipSync } from 'node:zlib';
import { closeServer, dist, launch, recordConsole, root, serve, withTimeout } from './harness.mjs';

const args = process.argv.slice(2);
const arg = (name, def) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 && args[i + 1] ? Number(args[i + 1]) : def;
};
const size = arg('size', 256);
const frames = arg('frames', 32);
const scene = join(root, 'assets/cornell_box/cornell_box.json');
const nativeBin = process.env.PENUMBRA_RENDER || join(root, 'build/tools/render/penumbra-render');

function sizes() {
  const files = ['penumbra_viewer.js', 'penumbra_viewer.wasm'].map((f) => join(dist, 'lib', f));
  const bytes = files.map((f) => statSync(f).size);
  const gz = files.map((f) => gzipSync(readFileSync(f), { level: 9 }).length);
  return { js: bytes[0], wasm: bytes[1], total: bytes[0] + bytes[1], gzip: gz[0] + gz[1] };
}

async function browser() {
  const server = await serve(dist);
  const b = await launch({ viewport: { width: size, height: size } });
  try {
    const page = b.context.pages()[0] || (await b.context.newPage());
    const lines = recordConsole(page);
    await page.goto(`http://127.0.0.1:${server.address().port}/index.html` +
                    `?frames=${frames}&pixelRatio=1&panel=0&adaptive=0`, { timeout: 20_000 });
    await page.waitForFunction(() => window.penumbraPage?.convergedCount > 0 ||
                                     window.penumbraPage?.errors.length || window.penumbraPage?.fatal,
                               null, { timeout: 300_000, polling: 200 });
    const result = await withTimeout(page.evaluate(async (n) => {
      const p = window.penumbraPage;
      if (p.errors.length || p.fatal) return { error: p.fatal || p.errors.join('; ') };
      return { ...(await p.viewer.benchmark({ frames: n })), report: p.viewer.info.report,
               context: p.viewer.info.context };
    }, frames), 600_000, 'benchmark');
    if (result.error) throw new Error(`${result.error}\n${lines.join('\n')}`);
    return result;
  } finally {
    await b.close();
    closeServer(server);
  }
}

function native() {
  if (!existsSync(nativeBin)) return { error: `${nativeBin} is not built` };
  const out = join(tmpdir(), `penumbra-bench-${process.pid}.png`);
  const r = spawnSync(nativeBin, [scene, '-o', out, '--size', `${size}x${size}`,
                                  '--frames', String(frames)],
                      { env: { ...process.env, MESA_GLES_VERSION_OVERRIDE: '3.0' },
                        encoding: 'utf8', timeout: 600_000 });
  const m = /(\d+) frames at (\d+)x(\d+) in ([\d.]+) s/.exec(r.stderr || '');
  if (r.status !== 0 || !m) return { error: `penumbra-render failed: ${r.stderr || r.error}` };
  return { frames: Number(m[1]), seconds: Number(m[4]), msPerFrame: (1000 * Number(m[4])) / Number(m[1]) };
}

const s = sizes();
console.log(`viewer module: penumbra_viewer.wasm ${s.wasm} B + penumbra_viewer.js ${s.js} B = ` +
            `${s.total} B (${(s.total / 1048576).toFixed(2)} MiB; gzip -9 ${s.gzip} B)`);
const n = native();
const w = await browser();
console.log(`Cornell box, ${size}x${size}, ${frames} frames, default settings of its scene file`);
console.log(`  Chromium / SwiftShader : ${w.msPerFrame.toFixed(1)} ms/frame back to back, ` +
            `${w.msPerFrameSynced.toFixed(1)} ms/frame with a read-back after each ` +
            `(${w.frames} frames, ${w.width}x${w.height})`);
console.log(n.error ? `  native penumbra-render: ${n.error}`
                    : `  native (llvmpipe)     : ${n.msPerFrame.toFixed(1)} ms/frame ` +
                      `(${n.frames} frames in ${n.seconds.toFixed(2)} s)`);
if (!n.error) console.log(`  ratio browser/native  : ${(w.msPerFrame / n.msPerFrame).toFixed(2)}`);
console.log(`  ${w.context}`);
