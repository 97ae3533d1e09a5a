// The displayed value of a radiance (exposure, tone mapping, sRGB, clamped as the 8-bit image
// is), in [0, 1]: what an automatic view's convergence measure compares.
#include "chunks/tonemap.glsl"
uniform float uExposureScale;  // 2^EV
uniform int uToneMapper;

vec3 displayed(vec4 radiance) {
  vec3 c = max(radiance.rgb * uExposureScale, vec3(0.0));
  return clamp(linearToSrgb(toneMap(c, uToneMapper)), 0.0, 1.0);
}
