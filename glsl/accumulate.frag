// Running mean of the intermediate frames: mean_n = mean_{n-1} + (x_n - mean_{n-1}) / n.
// A non-finite sample is dropped (keeps the previous mean), so one bad sample cannot poison
// the image.
uniform sampler2D uPrevious;
uniform sampler2D uCurrent;
uniform float uWeight;  // 1 / n
in vec2 vUv;
out vec4 fragColor;
bool finite(vec4 v) {
  return !(any(isnan(v)) || any(isinf(v)));
}
void main() {
  vec4 prev = texture(uPrevious, vUv);
  vec4 cur = texture(uCurrent, vUv);
  if (!finite(cur)) cur = prev;
  // Frame 1 becomes the mean as it is (RenderTargets::takeFrameAsMean): a non-finite pixel
  // there is replaced by the first finite sample after it.
  if (!finite(prev)) prev = cur;
  fragColor = uWeight >= 1.0 ? cur : prev + (cur - prev) * uWeight;
}
