#!/usr/bin/env node
// The path-tracer hand-off at the swap, for every evaluation scene: opens web/dist/handoff/ in
// headless Chromium (SwiftShader) once per scene at a small size, waits for Penumbra to converge
// and the path tracer to take over by the default rule, and writes docs/evaluation/handoff.md
// (the table), handoff.json (the figures) and handoff_<scene>.png (Penumbra converged | path
// tracer at the swap | 4 x difference). Needs tools/build-web first.
//   node tools/handoff-eval.mjs [--scenes cornell_box,glass] [--width 160] [--out docs/evaluation]
//                               [--max-tracing-s 240] [--report-only]
// --report-only rewrites handoff.md from handoff.json without rendering; with --scenes, the new
// rows replace those scenes' rows in handoff.json and the others stay.
import { mkdirSync, readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { join, relative } from 'node:path';
import { closeServer, dist, launch, recordConsole, root, serve } from '../web/tests/harness.mjs';

const args = process.argv.slice(2);
const opt = (k, d) => (args.includes(k) ? args[args.indexOf(k) + 1] : d);
const SCENES = opt('--scenes', 'cornell_box,material_grid,kitchen,glass,product,dense').split(',');
const WIDTH = Number(opt('--width', 160));
const OUT = opt('--out', join(root, 'docs/evaluation'));
const MAX_TRACING_MS = 1000 * Number(opt('--max-tracing-s', 240));
mkdirSync(OUT, { recursive: true });

// Every file of assets/ under /__scenes/ (the web build copies only some scenes into dist).
const extra = {};
for (const e of readdirSync(join(root, 'assets'), { recursive: true, withFileTypes: true })) {
  if (!e.isFile()) continue;
  const full = join(e.parentPath ?? e.path, e.name);
  extra[`/__scenes/${relative(join(root, 'assets'), full)}`] = full;
}
const REPORT_ONLY = args.includes('--report-only');
const server = REPORT_ONLY ? null : await serve(dist, extra);
const base = server && `http://127.0.0.1:${server.address().port}`;
const results = [];
for (const name of REPORT_ONLY ? [] : SCENES) {
  const file = `assets/${name}/${name}.json`;
  const scene = JSON.parse(readFileSync(join(root, file), 'utf8'));
  const [rw, rh] = scene.resolution || [1280, 720];
  const w = WIDTH, h = Math.round(WIDTH * rh / rw);
  const browser = await launch({ viewport: { width: w + 40, height: h + 80 } });
  const page = browser.context.pages()[0] || (await browser.context.newPage());
  const log = recordConsole(page);
  const t0 = Date.now();
  const r = { scene: name, width: w, height: h };
  try {
    const served = `/__scenes/${name}/`;
    const url = `${base}/handoff/index.html?size=${w}x${h}&budget=300&scene=${encodeURIComponent(served + name + '.json')}`;
    await page.goto(url, { timeout: 30_000 });
    await page.waitForFunction(() => window.handoff && ['tracing', 'error'].includes(window.handoff.phase),
                               null, { timeout: 300_000, polling: 1000 });
    await page.waitForFunction((ms) => window.handoff && (['pathtracer', 'error'].includes(window.handoff.phase) ||
                                                          window.handoff.tracingMs > ms),
                               MAX_TRACING_MS, { timeout: MAX_TRACING_MS + 300_000, polling: 1000 });
    const s = await page.evaluate(async () => {
      const { strip, stripNow, ...rest } = window.handoff;
      return { ...rest, strip: strip || (await stripNow()) };
    });
    if (s.phase === 'error') throw new Error(s.error);
    const swap = s.swaps[0];
    const last = s.checks.at(-1);
    Object.assign(r, {
      swapped: Boolean(swap), penumbraFrames: s.penumbraFrames, compileMs: s.compileMs,
      ...(swap || last), tracingMs: (swap || last).tracingMs,
    });
    if (!swap) Object.assign(r, { samples: s.samples, note: 'no swap within the time cap' });
    writeFileSync(join(OUT, `handoff_${name}.png`), Buffer.from(s.strip.split(',')[1], 'base64'));
  } catch (e) {
    r.error = `${e.message.split('\n')[0]} | ${log.filter((l) => /error/i.test(l)).slice(-3).join(' | ')}`;
  }
  r.wallS = (Date.now() - t0) / 1000;
  console.log(JSON.stringify(r));
  results.push(r);
  await browser.close();
}
if (server) closeServer(server);

// Keep the rows of scenes not run this time (handoff.json), in the default order.
let previous = [];
try { previous = JSON.parse(readFileSync(join(OUT, 'handoff.json'), 'utf8')); } catch {}
const ORDER = ['cornell_box', 'material_grid', 'kitchen', 'glass', 'product', 'dense', 'room_cm'];
for (const r of previous) if (!results.some((x) => x.scene === r.scene)) results.push(r);
results.sort((a, b) => ORDER.indexOf(a.scene) - ORDER.indexOf(b.scene));

// Cycles against Penumbra now (docs/evaluation/bias_budget.json, tools/bias-budget): the
// relative difference of their mean linear radiance, for comparison with the path tracer's.
let budget = {};
try { budget = JSON.parse(readFileSync(join(root, 'docs/evaluation/bias_budget.json'), 'utf8')); } catch {}
const cyclesVsPenumbra = (name) => {
  const m = budget[name]?.mean;
  return m && m.cycles && m.penumbra ? `${(100 * (m.cycles / m.penumbra - 1)).toFixed(1)} %` : '-';
};

const f = (v, d = 3) => (typeof v === 'number' ? v.toFixed(d) : '-');
// The renders' time: now, or with --report-only the one the report already states.
let generated = new Date().toISOString().slice(0, 16).replace('T', ' ');
if (REPORT_ONLY) {
  try {
    generated = /on (\d{4}-\d\d-\d\d \d\d:\d\d) UTC/.exec(readFileSync(join(OUT, 'handoff.md'), 'utf8'))[1];
  } catch {}
}
const L = [
  '# The path-tracer hand-off at the swap',
  '',
  `Generated by \`node tools/handoff-eval.mjs\` on ${generated} UTC ` +
  'from the hand-off page (`web/dist/handoff/`, [docs/web/handoff.md](../web/handoff.md#the-path-tracer-hand-off)) in headless ' +
  'Chromium on SwiftShader (2 shared cores): Penumbra (the scene file\'s settings and frame count) converges, ' +
  'then three-gpu-pathtracer 0.0.26 (8 bounces) refines the same view with a 300 ms budget per animation ' +
  'frame until the default swap rule fires (from 16 samples on: noise N <= 0.5 x estimated bias B, or ' +
  'N <= 1/255; N and B from the path tracer\'s snapshots at n and 2n samples). The views are small (software GPU): ' +
  `${WIDTH} pixels wide at the scene's aspect ratio. Luminance is the mean Rec. 709 luminance of the ` +
  'displayed images (exposure, Khronos PBR Neutral, sRGB); SSIM is over 7x7 windows of that luminance. ' +
  'The path tracer\'s time excludes its shader compilation (the compile column, once per page). ' +
  'The last column is, for comparison, how much brighter Cycles is than Penumbra (mean linear radiance, ' +
  '[bias-budget.md](bias-budget.md), 256 pixels wide): Penumbra is within a few per cent of Cycles, so ' +
  'where the path tracer differs from Penumbra by more, it is the path tracer that is off (on the Cornell ' +
  'box it is 11 % darker than a 256-sample Cycles render in displayed luminance, [docs/web/handoff.md](../web/handoff.md#the-path-tracer-hand-off)). ' +
  'Lamp faces are drawn over the path tracer\'s image as Penumbra draws them. The swap comes at a power of ' +
  'two, and the noise estimate is itself noisy, so the sample count at the swap varies by a factor of 2 ' +
  'between runs.',
  '',
  '| scene | size | Penumbra frames | path tracer samples | path tracer time (s) | compile (s) | noise N | bias B | luminance Penumbra | luminance path tracer | difference | SSIM | Cycles vs Penumbra (bias budget) |',
  '|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|',
];
for (const r of results) {
  if (r.error) {
    L.push(`| ${r.scene} | ${r.width}x${r.height} | failed: ${r.error.replace(/\|/g, '/')} ||||||||||| |`);
    continue;
  }
  const rel = r.penumbraLuminance ? ` (${(100 * r.relativeLuminanceDifference).toFixed(1)} %)` : '';
  L.push(`| ${r.scene}${r.swapped ? '' : ' (no swap yet)'} | ${r.width}x${r.height} | ${r.penumbraFrames} | ${r.samples} | ` +
         `${f(r.tracingMs / 1000, 1)} | ${f(r.compileMs / 1000, 1)} | ${f(r.noise, 4)} | ${f(r.bias, 4)} | ` +
         `${f(r.penumbraLuminance)} | ${f(r.pathTracerLuminance)} | ${f(r.luminanceDifference)}${rel} | ${f(r.ssim)} | ` +
         `${cyclesVsPenumbra(r.scene)} |`);
}
L.push('');
L.push('Rows marked "no swap yet" ran out of the time cap (`--max-tracing-s`) before the rule fired; their ' +
       'figures are the last check\'s, and their luminance and SSIM columns are empty.');
L.push('');
for (const r of results.filter((x) => !x.error)) {
  L.push(`**${r.scene}**: Penumbra converged | path tracer at ${r.swapped ? 'the swap' : 'the cap'} (${r.samples} samples) | 4 x |difference|`);
  L.push('');
  L.push(`![${r.scene} hand-off strip](handoff_${r.scene}.png)`);
  L.push('');
}
writeFileSync(join(OUT, 'handoff.md'), L.join('\n'));
if (!REPORT_ONLY) writeFileSync(join(OUT, 'handoff.json'), JSON.stringify(results, null, 2));
console.log(`wrote ${relative(root, join(OUT, 'handoff.md'))}`);
