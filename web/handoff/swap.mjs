// The hand-off rule and the image measures behind it (docs/web/handoff.md, "The path-tracer hand-off").
// Pure functions on display images: {width, height, data} with RGBA values in [0, 1] (a
// Float32Array or any array), row 0 at the top. No DOM, no GL: node tests call them directly.
//
// The rule. A converged Penumbra image P has an error that does not shrink (its bias); the path
// tracer's image S_n after n samples has an error that does (its noise). Keep snapshots of the
// path tracer at n = 2^k samples. At 2n:
//   noise  N = RMS(S_2n - S_n)   (S_2n = (S_n + S'_n) / 2 with S'_n independent of S_n, so
//                                 S_n - S_2n = (S_n - S'_n) / 2 has the variance of S_2n's noise)
//   diff   D = RMS(S_2n - P)     (E[D^2] = B^2 + N^2: Penumbra's bias plus the path tracer's noise)
//   bias   B = sqrt(max(0, D^2 - N^2))
// and swap when N <= factor * B, or
// when N <= floor (default 1/255: the path tracer is converged at display precision, whatever
// Penumbra's bias). RMS is over R, G and B of the display values. With factor 1 the swap would
// come as soon as the path tracer's RMS error is the smaller one, but per-pixel noise is far more
// visible than the smooth, low-frequency bias of a converged Penumbra image (measured: the swap
// came at 8 samples, visibly grainy), so the default asks for half: noise <= bias / 2, that is
// the noise's share of the path tracer's squared difference to Penumbra at most 1/5.
// minSamples: the path tracer's display image is tone-mapped from its running mean, and at a
// handful of samples a rare bright path (a sun, a small light) is mostly missing, so the image is
// darker than it will be and its noise is underestimated; on the dense scene, with a sun, the
// rule fired at 2 samples with the path tracer 19 % too dark. From 16 samples on it did not.

export const RULE_DEFAULTS = Object.freeze({
  factor: 0.5,        // swap when noise <= factor x estimated bias
  floor: 1 / 255,     // or when the noise is below one display step
  minSamples: 16,     // no swap before: at few samples the display image is not yet unbiased
});

// Root mean square of a - b over RGB.
export function rms(a, b) {
  sameSize(a, b);
  let sum = 0;
  const n = a.width * a.height;
  for (let i = 0; i < n * 4; i += 4) {
    for (let c = 0; c < 3; c++) {
      const d = a.data[i + c] - b.data[i + c];
      sum += d * d;
    }
  }
  return Math.sqrt(sum / (n * 3));
}

// One comparison of the rule: `previous` is the path tracer at n samples, `current` at 2n,
// `penumbra` the converged Penumbra image. Returns {noise, diff, bias, swap, why}.
export function evaluateSwap({ previous, current, penumbra, samples }, rule = RULE_DEFAULTS) {
  const r = { ...RULE_DEFAULTS, ...rule };
  const noise = rms(current, previous);
  const diff = rms(current, penumbra);
  const bias = Math.sqrt(Math.max(0, diff * diff - noise * noise));
  let why = '';
  if (samples >= r.minSamples) {
    if (noise <= r.factor * bias) why = `noise ${noise.toFixed(4)} <= ${r.factor} x bias ${bias.toFixed(4)}`;
    else if (noise <= r.floor) why = `noise ${noise.toFixed(4)} <= floor ${r.floor.toFixed(4)}`;
  }
  return { noise, diff, bias, swap: why !== '', why };
}

// Rec. 709 luminance of the display values, per pixel.
export function luminance(img) {
  const n = img.width * img.height;
  const y = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    const o = i * 4;
    y[i] = 0.2126 * img.data[o] + 0.7152 * img.data[o + 1] + 0.0722 * img.data[o + 2];
  }
  return y;
}

export function meanLuminance(img) {
  const y = luminance(img);
  let s = 0;
  for (const v of y) s += v;
  return s / y.length;
}

// Mean SSIM of the luminance (Wang et al. 2004): 7x7 uniform windows (every window that fits,
// stride 1), K1 = 0.01, K2 = 0.03, dynamic range 1.
export function ssim(a, b, win = 7) {
  sameSize(a, b);
  const { width: w, height: h } = a;
  const ya = luminance(a), yb = luminance(b);
  const c1 = 0.01 ** 2, c2 = 0.03 ** 2;
  const k = Math.min(win, w, h);
  const n = k * k;
  let total = 0, count = 0;
  for (let y0 = 0; y0 + k <= h; y0++) {
    for (let x0 = 0; x0 + k <= w; x0++) {
      let sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
      for (let y = y0; y < y0 + k; y++) {
        for (let x = x0; x < x0 + k; x++) {
          const p = ya[y * w + x], q = yb[y * w + x];
          sa += p; sb += q; saa += p * p; sbb += q * q; sab += p * q;
        }
      }
      const ma = sa / n, mb = sb / n;
      const va = saa / n - ma * ma, vb = sbb / n - mb * mb, cov = sab / n - ma * mb;
      total += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
      count++;
    }
  }
  return total / count;
}

// |a - b| per pixel (RGB, alpha 1), scaled by `gain` for visibility: the strip's third picture.
export function differenceImage(a, b, gain = 4) {
  sameSize(a, b);
  const data = new Float32Array(a.width * a.height * 4);
  for (let i = 0; i < data.length; i += 4) {
    for (let c = 0; c < 3; c++) data[i + c] = Math.min(1, gain * Math.abs(a.data[i + c] - b.data[i + c]));
    data[i + 3] = 1;
  }
  return { width: a.width, height: a.height, data };
}

// The measures at the swap: mean luminance of both, their difference, and SSIM.
export function agreement(penumbra, pathTracer) {
  const lp = meanLuminance(penumbra), lt = meanLuminance(pathTracer);
  return { penumbraLuminance: lp, pathTracerLuminance: lt, luminanceDifference: lt - lp,
           relativeLuminanceDifference: lp > 0 ? (lt - lp) / lp : 0, ssim: ssim(penumbra, pathTracer) };
}

function sameSize(a, b) {
  if (a.width !== b.width || a.height !== b.height) {
    throw new Error(`image sizes differ: ${a.width}x${a.height} vs ${b.width}x${b.height}`);
  }
}
