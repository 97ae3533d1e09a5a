// Adds the frame target's sample to the running mean (chunks/accumulate.glsl).
#include "chunks/accumulate.glsl"
uniform sampler2D uPrevious;
uniform sampler2D uCurrent;
in vec2 vUv;
out vec4 fragColor;
void main() {
  fragColor = runningMean(texture(uPrevious, vUv), texture(uCurrent, vUv));
}
