// Post pass: exposure and tone mapping of the accumulated radiance to display sRGB.
#include "chunks/tonemap.glsl"
uniform sampler2D uRadiance;
uniform float uExposureScale;  // 2^EV
uniform int uToneMapper;
// 1: a transparent background (RenderSettings::transparentBackground): the mean's alpha is the
// scene's coverage and its colour coverage-weighted radiance, divided out before tone mapping;
// the output has straight alpha (a PNG's, and the browser canvas's: premultipliedAlpha false).
uniform float uTransparent;
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

// A texel of the mean as displayed, its colour premultiplied by its alpha (1 when opaque).
vec4 displayedTexel(vec4 t) {
  float a = uTransparent > 0.5 ? saturate(t.a) : 1.0;
  return vec4(displayed(t.rgb / max(a, 1e-4)) * a, a);
}

vec4 straight(vec4 c) {
  return vec4(c.rgb / max(c.a, 1e-4), c.a);
}

void main() {
#ifndef PN_FILTERED
  fragColor = straight(displayedTexel(texture(uRadiance, vUv)));
#else
  ivec2 size = textureSize(uRadiance, 0);
  vec2 p = vUv * vec2(size) - 0.5;
  vec2 f = fract(p);
  ivec2 i = ivec2(floor(p)), hi = size - 1;
  vec4 a = displayedTexel(texelFetch(uRadiance, clamp(i, ivec2(0), hi), 0));
  vec4 b = displayedTexel(texelFetch(uRadiance, clamp(i + ivec2(1, 0), ivec2(0), hi), 0));
  vec4 c = displayedTexel(texelFetch(uRadiance, clamp(i + ivec2(0, 1), ivec2(0), hi), 0));
  vec4 d = displayedTexel(texelFetch(uRadiance, clamp(i + ivec2(1, 1), ivec2(0), hi), 0));
  fragColor = straight(mix(mix(a, b, f.x), mix(c, d, f.x), f.y));
#endif
}
