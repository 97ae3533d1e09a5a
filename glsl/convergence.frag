// An automatic view's convergence measure (progressive/convergence.h): per tile of
// PN_TILE x PN_TILE pixels, the RMS change of the displayed image (exposure, tone mapping,
// sRGB, clamped as the 8-bit image is; in 8-bit steps) from the previous checkpoint's mean to
// the running mean, and its largest change (one channel of one pixel). One output texel a
// tile: (RMS, values counted, largest, 1).
#include "chunks/tonemap.glsl"
uniform sampler2D uCurrent;
uniform sampler2D uPrevious;
uniform float uExposureScale;  // 2^EV
uniform int uToneMapper;
out vec4 fragColor;

vec3 displayed(vec4 radiance) {
  vec3 c = max(radiance.rgb * uExposureScale, vec3(0.0));
  return clamp(linearToSrgb(toneMap(c, uToneMapper)), 0.0, 1.0);
}

void main() {
  ivec2 size = textureSize(uCurrent, 0);
  ivec2 base = ivec2(gl_FragCoord.xy) * PN_TILE;
  float sum = 0.0;
  float count = 0.0;
  float largest = 0.0;
  for (int y = 0; y < PN_TILE; ++y) {
    for (int x = 0; x < PN_TILE; ++x) {
      ivec2 p = base + ivec2(x, y);
      if (p.x >= size.x || p.y >= size.y) continue;
      vec3 d = (displayed(texelFetch(uCurrent, p, 0)) - displayed(texelFetch(uPrevious, p, 0))) *
               255.0;
      sum += dot(d, d);
      vec3 a = abs(d);
      largest = max(largest, max(a.r, max(a.g, a.b)));
      count += 3.0;
    }
  }
  fragColor = vec4(sqrt(sum / max(count, 1.0)), count, largest, 1.0);
}
