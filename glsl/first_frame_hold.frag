// The displayed image of an early frame with stochastic transparency: the running mean mixed
// with frame 1's alpha-blended image (progressive/first_frame_hold.h). A non-finite mean
// texel (dropped samples keep it finite, but a host may hand any) shows frame 1.
uniform sampler2D uMean;
uniform sampler2D uFirst;
uniform float uHold;  // frame 1's weight, in (0, 1)
in vec2 vUv;
out vec4 fragColor;
void main() {
  vec4 mean = texture(uMean, vUv);
  vec4 first = texture(uFirst, vUv);
  if (any(isnan(mean)) || any(isinf(mean))) mean = first;
  fragColor = mix(mean, first, uHold);
}
