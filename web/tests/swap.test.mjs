// The hand-off page's swap rule and image measures (web/handoff/swap.mjs), in node alone with
// made-up images; and that the path tracer stays out of Penumbra's core bundle (web/lib).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { root } from './harness.mjs';
import { RULE_DEFAULTS, agreement, evaluateSwap, meanLuminance, rms, ssim } from '../handoff/swap.mjs';

// A deterministic generator, so the tests do not depend on Math.random.
function rng(seed) {
  let s = seed >>> 0;
  return () => {
    s = (Math.imul(s ^ (s >>> 15), 0x2c1b3c6d) + 0x6d2b79f5) >>> 0;
    return s / 2 ** 32;
  };
}

// A smooth test picture (a gradient with a bright square), plus `bias` and Gaussian-ish noise
// of standard deviation `sigma` per channel.
function picture(w, h, { bias = 0, sigma = 0, seed = 1 } = {}) {
  const r = rng(seed);
  const data = new Float32Array(w * h * 4);
  for (let y = 0; y < h; y++) {
    for (let x = 0; x < w; x++) {
      const base = 0.2 + 0.5 * (x / w) + (x > w / 3 && x < w / 2 && y > h / 3 && y < h / 2 ? 0.2 : 0);
      for (let c = 0; c < 3; c++) {
        // Sum of 3 uniforms: mean 1.5, variance 1/4.
        const n = (r() + r() + r() - 1.5) * 2 * sigma;
        data[(y * w + x) * 4 + c] = base + bias + n;
      }
      data[(y * w + x) * 4 + 3] = 1;
    }
  }
  return { width: w, height: h, data };
}

test('rms, mean luminance and SSIM of known pictures', () => {
  const a = picture(32, 32);
  assert.equal(rms(a, a), 0);
  assert.ok(Math.abs(rms(a, picture(32, 32, { bias: 0.1 })) - 0.1) < 1e-6);
  const grey = { width: 2, height: 1, data: [0.5, 0.5, 0.5, 1, 0.5, 0.5, 0.5, 1] };
  assert.ok(Math.abs(meanLuminance(grey) - 0.5) < 1e-12);
  assert.ok(Math.abs(ssim(a, a) - 1) < 1e-12);
  const noisy = ssim(a, picture(32, 32, { sigma: 0.1, seed: 3 }));
  const lessNoisy = ssim(a, picture(32, 32, { sigma: 0.02, seed: 3 }));
  assert.ok(noisy < lessNoisy && lessNoisy < 1, `SSIM ${noisy} < ${lessNoisy} < 1`);
  const agree = agreement(a, picture(32, 32, { bias: 0.05 }));
  assert.ok(Math.abs(agree.luminanceDifference - 0.05) < 1e-6);
  assert.throws(() => rms(a, picture(16, 32)), /image sizes differ: 32x32 vs 16x32/);
});

test('the noise estimate from snapshots at n and 2n samples matches the true noise', () => {
  // A path tracer with per-sample noise s: S_n has noise s / sqrt(n). S_2n is the mean of S_n
  // and an independent S'_n, as the path tracer's running mean is.
  const s = 0.4, n = 16;
  const truth = picture(64, 64);
  const sn = picture(64, 64, { sigma: s / Math.sqrt(n), seed: 11 });
  const sn2 = picture(64, 64, { sigma: s / Math.sqrt(n), seed: 12 });
  const s2n = { ...truth, data: sn.data.map((v, i) => (v + sn2.data[i]) / 2) };
  const penumbra = picture(64, 64, { bias: 0.03 });
  const r = evaluateSwap({ previous: sn, current: s2n, penumbra, samples: 2 * n });
  const trueNoise = rms(s2n, truth);
  assert.ok(Math.abs(r.noise - trueNoise) / trueNoise < 0.05, `noise ${r.noise} vs true ${trueNoise}`);
  assert.ok(Math.abs(r.bias - 0.03) < 0.006, `bias ${r.bias} vs 0.03`);
});

test('the rule: swap when noise <= factor x bias or noise <= floor, never before minSamples', () => {
  const truth = picture(48, 48);
  // The path tracer's image has noise `noise`; its snapshot at half the samples differs from it
  // by as much (so the estimate is `noise`); Penumbra is off by `bias`.
  const at = (noise, bias, samples, rule) => {
    const current = picture(48, 48, { sigma: noise, seed: samples });
    const extra = picture(48, 48, { sigma: noise, seed: samples + 1000 });
    const previous = { ...current, data: current.data.map((v, i) => v + extra.data[i] - truth.data[i]) };
    return evaluateSwap({ previous, current, penumbra: picture(48, 48, { bias }), samples }, rule);
  };
  // Noise 0.1 against bias 0.05: no swap (default factor 0.5).
  assert.equal(RULE_DEFAULTS.factor, 0.5);
  assert.equal(RULE_DEFAULTS.minSamples, 16);
  assert.equal(at(0.1, 0.05, 16).swap, false);
  // Noise 0.02 against bias 0.05: swap.
  const yes = at(0.02, 0.05, 16);
  assert.ok(yes.swap && /<= 0.5 x bias/.test(yes.why), yes.why);
  // A Penumbra image without bias: only the floor lets the path tracer take over.
  assert.equal(at(0.02, 0, 16).swap, false);
  const floor = at(0.001, 0, 64);
  assert.ok(floor.swap && /floor/.test(floor.why), floor.why);
  // Thresholds can be changed (the page takes them from its URL).
  assert.equal(at(0.05, 0.06, 16, { factor: 1 }).swap, true);
  // Never before minSamples, however clear the case.
  assert.equal(at(0.02, 0.05, 8).swap, false);
  assert.equal(at(0.02, 0.05, 8, { minSamples: 8 }).swap, true);
});

test('the path tracer stays out of the core bundle: nothing in web/lib imports it', () => {
  const lib = join(root, 'web/lib');
  for (const f of readdirSync(lib).filter((n) => n.endsWith('.mjs'))) {
    const text = readFileSync(join(lib, f), 'utf8');
    assert.doesNotMatch(text, /from\s+['"](three|three-gpu-pathtracer|three-mesh-bvh)|handoff\//, f);
  }
});
