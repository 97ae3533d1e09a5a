// The displayed image of an early frame with stochastic transparency: the running mean mixed
// with frame 1's alpha-blended image (progressive/first_frame_hold.h). A pixel frame 1 left
// non-finite (the mean drops it for the first finite sample after it: chunks/accumulate.glsl)
// shows the mean alone.
#include "chunks/accumulate.glsl"
uniform sampler2D uMean;
uniform sampler2D uFirst;
uniform float uHold;  // frame 1's weight, in (0, 1)
in vec2 vUv;
out vec4 fragColor;
void main() {
  vec4 mean = texture(uMean, vUv);
  vec4 first = texture(uFirst, vUv);
  fragColor = finiteSample(first) ? mix(mean, first, uHold) : mean;
}
