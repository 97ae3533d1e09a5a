// Post pass: exposure and tone mapping of the accumulated radiance to display sRGB.
#include "chunks/tonemap.glsl"
uniform sampler2D uRadiance;
uniform float uExposureScale;  // 2^EV
uniform int uToneMapper;
// PN_FILTERED, a program of its own: the viewport is larger than the image (a browser's render
// size below its canvas): the displayed colours of the four nearest texels interpolated, as a
// filtered upscale of the 8-bit image would be (float targets get no filtering from their
// sampler: RGBA32F is not filterable in WebGL2), instead of hard pixel steps. Interpolating
// radiance before tone mapping would put a bright edge's whole step into one pixel. Not a
// uniform branch: a software GL (llvmpipe, SwiftShader) ran both sides, four tone mappings a
// pixel, and every tone mapping took 4.5 times as long (issue #59).
in vec2 vUv;
out vec4 fragColor;

vec3 displayed(vec3 radiance) {
  return linearToSrgb(toneMap(max(radiance * uExposureScale, vec3(0.0)), uToneMapper));
}

void main() {
#ifndef PN_FILTERED
  fragColor = vec4(displayed(texture(uRadiance, vUv).rgb), 1.0);
#else
  ivec2 size = textureSize(uRadiance, 0);
  vec2 p = vUv * vec2(size) - 0.5;
  vec2 f = fract(p);
  ivec2 i = ivec2(floor(p)), hi = size - 1;
  vec3 a = displayed(texelFetch(uRadiance, clamp(i, ivec2(0), hi), 0).rgb);
  vec3 b = displayed(texelFetch(uRadiance, clamp(i + ivec2(1, 0), ivec2(0), hi), 0).rgb);
  vec3 c = displayed(texelFetch(uRadiance, clamp(i + ivec2(0, 1), ivec2(0), hi), 0).rgb);
  vec3 d = displayed(texelFetch(uRadiance, clamp(i + ivec2(1, 1), ivec2(0), hi), 0).rgb);
  fragColor = vec4(mix(mix(a, b, f.x), mix(c, d, f.x), f.y), 1.0);
#endif
}
