// Times the hand-off page (web/dist/handoff/) as a person meets it: load -> Penumbra converged
// -> path tracer's shader compiled (in its worker) -> path tracer shown (the swap), with the
// page's long tasks and the delay of synthetic pointer input during the compile.
//   node web/tests/bench_handoff.mjs [--size WxH] [--scene URL] [--timeout S]
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { closeServer, dist, launch, outDir, serve } from './harness.mjs';

mkdirSync(outDir, { recursive: true });

const args = process.argv.slice(2);
const arg = (k, d) => (args.includes(k) ? args[args.indexOf(k) + 1] : d);
const [vw, vh] = arg('--size', '1366x768').split('x').map(Number);
const timeoutS = Number(arg('--timeout', 400));
const server = await serve(dist);
const browser = await launch({ viewport: { width: vw, height: vh } });
const page = browser.context.pages()[0] || (await browser.context.newPage());
await page.addInitScript(() => {
  window.__long = [];
  new PerformanceObserver((l) => { for (const e of l.getEntries()) window.__long.push([Math.round(e.startTime), Math.round(e.duration)]); })
    .observe({ type: 'longtask', buffered: true });
  // Input delay: a timer every 100 ms notes how late it runs.
  window.__late = [];
  let due = performance.now() + 100;
  setInterval(() => { const t = performance.now(); window.__late.push([Math.round(t), Math.round(t - due)]); due = t + 100; }, 100);
});
const scene = arg('--scene', null);
const query = [scene && `scene=${encodeURIComponent(scene)}`, arg('--query', null)].filter(Boolean).join('&');
const url = `http://127.0.0.1:${server.address().port}/handoff/index.html${query ? `?${query}` : ''}`;
const t0 = Date.now();
await page.goto(url);
const marks = {};
let last = '';
for (;;) {
  const s = await page.evaluate(() => { const { strip, stripNow, checks, ...r } = window.handoff || {}; return { ...r, now: performance.now() }; });
  const key = `${s.phase}/${s.compileMs != null}`;
  if (key !== last) { marks[key] = ((Date.now() - t0) / 1000).toFixed(1); last = key; console.log(`${marks[key]} s: ${key} samples ${s.samples} ${s.error || ''}`); }
  if (s.phase === 'pathtracer' || s.phase === 'error' || Date.now() - t0 > timeoutS * 1000) { console.log(JSON.stringify(s)); break; }
  await new Promise((r) => setTimeout(r, 500));
}
const { long, late } = await page.evaluate(() => ({ long: window.__long, late: window.__late }));
const maxLate = late.reduce((m, [, d]) => Math.max(m, d), 0);
console.log(`long tasks: ${long.length}, longest ${long.reduce((m, [, d]) => Math.max(m, d), 0)} ms; latest timer ${maxLate} ms`);
console.log(JSON.stringify(long.filter(([, d]) => d > 250)));
const strip = await page.evaluate(() => window.handoff.strip);
if (strip) writeFileSync(join(outDir, 'bench-handoff-strip.png'), Buffer.from(strip.split(',')[1], 'base64'));
await page.screenshot({ path: join(outDir, 'bench-handoff.png') });
console.log(`page and strip: ${join(outDir, 'bench-handoff.png')}, bench-handoff-strip.png`);
await browser.close();
closeServer(server);
