// The path-tracer hand-off page (web/handoff/) headless on the Cornell box at 64x64: Penumbra
// converges, three-gpu-pathtracer refines until the swap rule fires and the page cross-fades to
// it, the two displayed images agree at the swap (mean luminance, SSIM), and a camera drag
// brings Penumbra back at once, after which the hand-off happens again for the new view.
// Under SwiftShader the path tracer's shader takes 45-60 s to compile (once per page), a sample
// about 100 ms at this size. Figures go to build-web/test-output/handoff.json, the strip
// (Penumbra | path tracer | 4 x difference) to handoff-strip.png, a failure's page to
// handoff-failed.png.
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { closeServer, dist, launch, outDir, recordConsole, serve, withTimeout } from './harness.mjs';

const SIZE = 64;
// Agreement at the swap, displayed images (scene exposure, PBR Neutral, sRGB). Measured at 64x64:
// see docs/web.md. The path tracer at the swap still carries noise (the rule lets it take over
// when its noise is half Penumbra's estimated bias). Penumbra, with its probe volume, is within
// 2 % of Cycles' mean radiance in the Cornell box (docs/evaluation/probe-volume.md); the page's
// path tracer measured 10-15 % darker than it at the swap (0.270 against 0.314; before the
// probe volume it was 12-20 % brighter, when Penumbra lacked the multiple-bounce light). So
// the two may differ either way, by at most 30 %: (L_pt - L_penumbra) / L_penumbra in
// [-0.3, 0.3] (with the path tracer's exposure left at 0 EV instead of the scene's +1 it is
// -0.4 or below and fails). SSIM of the luminance at
// least 0.4 (measured 0.55-0.71: the path tracer's noise at 16-32 samples bounds it; a field of
// view 15 % too wide gives 0.21).
const LUMINANCE_RANGE = [-0.3, 0.3];
const MIN_SSIM = 0.4;
const FIRST_SWAP_MS = 150_000;       // load, converge, compile (45-60 s), samples
const TEST_MS = 260_000;  // under tools/test-web's 300 s for this file

let server, browser, page;
const consoleLines = [];
const figures = {};

before(async () => {
  mkdirSync(outDir, { recursive: true });
  for (const f of ['handoff-strip.png', 'handoff-failed.png', 'handoff.json']) rmSync(join(outDir, f), { force: true });
  if (!existsSync(join(dist, 'handoff/vendor/three-gpu-pathtracer/src/index.js'))) {
    throw new Error(`${dist}/handoff is not built: run tools/build-web first`);
  }
  server = await serve(dist);
  browser = await launch({ viewport: { width: 300, height: 300 } });
  page = browser.context.pages()[0] || (await browser.context.newPage());
  recordConsole(page, consoleLines);
});

after(async () => {
  writeFileSync(join(outDir, 'handoff.json'), JSON.stringify(figures, null, 2));
  await browser?.close();
  closeServer(server);
});

const state = () => withTimeout(page.evaluate(() => {
  const { strip, stripNow, ...rest } = window.handoff || {};
  return { ...rest, opacity: getComputedStyle(document.getElementById('pathtracer')).opacity,
           penumbra: window.handoff ? null : null };
}), 150_000, 'read state');  // the shader compile blocks the page for 45-60 s alone, past
// 90 s when the browser tests beside it load the machine (a clean CI run of 2026-11-28)

async function waitPhase(phase, ms, what) {
  try {
    await page.waitForFunction((p) => window.handoff && (window.handoff.phase === p || window.handoff.phase === 'error'),
                               phase, { timeout: ms, polling: 500 });
  } catch (e) {
    throw await failure(`${what}: ${e.message.split('\n')[0]}`);
  }
  const s = await state();
  if (s.phase === 'error') throw await failure(`${what}: the page failed: ${s.error}`);
  return s;
}

async function failure(message) {
  await page.screenshot({ path: join(outDir, 'handoff-failed.png') }).catch(() => {});
  const s = await state().catch(() => ({}));
  return new Error(`${message}\nstate: ${JSON.stringify(s)}\nconsole:\n${consoleLines.slice(-20).join('\n')}`);
}

async function saveStrip() {
  const strip = await page.evaluate(() => window.handoff.strip);
  if (strip) writeFileSync(join(outDir, 'handoff-strip.png'), Buffer.from(strip.split(',')[1], 'base64'));
}

function checkSwap(s, label) {
  const swap = s.swaps.at(-1);
  const { factor, floor, minSamples } = s.rule;
  // The rule fired at this check and at no earlier one since the camera last changed.
  assert.ok(swap.noise <= factor * swap.bias || swap.noise <= floor, `${label}: ${JSON.stringify(swap)}`);
  assert.ok(swap.samples >= minSamples);
  const before = s.checks.slice(0, -1).filter((c) => c.samples >= minSamples);
  for (const c of before) {
    assert.ok(!(c.noise <= factor * c.bias || c.noise <= floor), `${label}: rule held earlier at ${c.samples} samples`);
  }
  assert.deepEqual(s.checks.at(-1).samples, swap.samples);
  const rel = swap.relativeLuminanceDifference;
  figures[label] = { samples: swap.samples, tracingMs: Math.round(swap.tracingMs), noise: swap.noise,
                     bias: swap.bias, penumbraLuminance: swap.penumbraLuminance,
                     pathTracerLuminance: swap.pathTracerLuminance, relativeLuminance: swap.relativeLuminanceDifference,
                     ssim: swap.ssim, compileMs: s.compileMs && Math.round(s.compileMs) };
  if (rel < LUMINANCE_RANGE[0] || rel > LUMINANCE_RANGE[1] || swap.ssim < MIN_SSIM) {
    throw new Error(`${label}: disagreement at the swap: mean luminance ${swap.pathTracerLuminance.toFixed(4)} vs ` +
                    `${swap.penumbraLuminance.toFixed(4)} (relative ${rel.toFixed(3)}, bounds ${LUMINANCE_RANGE.join('..')}), ` +
                    `SSIM ${swap.ssim.toFixed(3)} (bound ${MIN_SSIM}); strip in handoff-strip.png`);
  }
}

test('Penumbra converges, the path tracer takes over by the rule, a camera move brings Penumbra back', { timeout: TEST_MS }, async () => {
  const url = `http://127.0.0.1:${server.address().port}/handoff/index.html?size=${SIZE}x${SIZE}&budget=200`;
  await page.goto(url, { timeout: 20_000 });

  // Penumbra first: it converges while the path tracer waits. The phase turns to 'tracing'
  // just before the path tracer's shader compile, which blocks the page (and this wait's
  // polling) for 45-60 s: the bound covers convergence plus the compile on a loaded machine.
  const tracing = await waitPhase('tracing', 120_000, 'Penumbra did not converge');
  assert.ok(tracing.penumbraFrames >= 1, `Penumbra frames ${tracing.penumbraFrames}`);
  assert.equal(tracing.opacity, '0', 'the path tracer is hidden before the swap');
  assert.deepEqual(tracing.rule, { factor: 0.5, floor: 1 / 255, minSamples: 16 }, 'the default rule');

  // The path tracer takes over when the rule fires, with a cross-fade.
  const swapped = await waitPhase('pathtracer', FIRST_SWAP_MS, 'the path tracer never took over');
  await saveStrip();
  assert.equal(swapped.swaps.length, 1);
  checkSwap(swapped, 'first swap');
  await page.waitForFunction(() => getComputedStyle(document.getElementById('pathtracer')).opacity === '1',
                             null, { timeout: 10_000 });
  // It keeps refining after the swap.
  const n = swapped.samples;
  await page.waitForFunction((k) => window.handoff.samples > k, n, { timeout: 30_000, polling: 250 });

  // A drag orbits Penumbra's camera: Penumbra shows again at once (no fade back).
  await page.mouse.move(20, 32);
  await page.mouse.down();
  for (let i = 1; i <= 6; i++) await page.mouse.move(20 + 4 * i, 32 + i);
  await page.mouse.up();
  const back = await state();
  assert.ok(back.cameraMoves >= 1, 'the camera event reached the page');
  assert.ok(back.phase === 'penumbra' || back.phase === 'tracing', `phase after the drag: ${back.phase}`);
  assert.equal(back.opacity, '0', 'the path tracer is hidden at once on a camera move');

  // The new view converges and is handed over again (the shader is compiled by now).
  await waitPhase('pathtracer', 90_000, 'no second hand-off after the camera move');
  const again = await state();
  assert.equal(again.swaps.length, 2);
  checkSwap(again, 'after the camera move');
  figures.pathTracerMsPerSample = again.swaps[1].tracingMs / again.swaps[1].samples;
});
