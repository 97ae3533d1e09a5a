// The running mean of the intermediate frames, mean_n = mean_{n-1} + (x_n - mean_{n-1}) / n,
// for the accumulate pass and for the passes that add their sample as they draw it
// (PN_ACCUMULATE). A non-finite sample is dropped (keeps the previous mean), so one bad sample
// cannot poison the image.
uniform float uWeight;  // 1 / n

bool finiteSample(vec4 v) {
  return !(any(isnan(v)) || any(isinf(v)));
}

vec4 runningMean(vec4 prev, vec4 cur) {
  if (!finiteSample(cur)) cur = prev;
  // Frame 1 becomes the mean as it is (RenderTargets::takeFrameAsMean): a non-finite pixel
  // there is replaced by the first finite sample after it.
  if (!finiteSample(prev)) prev = cur;
  return uWeight >= 1.0 ? cur : prev + (cur - prev) * uWeight;
}
