// Post pass: exposure and tone mapping of the accumulated radiance to display sRGB.
#include "chunks/tonemap.glsl"
uniform sampler2D uRadiance;
uniform float uExposureScale;  // 2^EV
uniform int uToneMapper;
in vec2 vUv;
out vec4 fragColor;
void main() {
  vec3 c = texture(uRadiance, vUv).rgb * uExposureScale;
  fragColor = vec4(linearToSrgb(toneMap(max(c, vec3(0.0)), uToneMapper)), 1.0);
}
