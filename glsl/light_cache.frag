// The per-view area-light cache (passes/lighting_pass.h): where the frame's depth pass left
// the surfaces, each of PN_LIGHT_CACHE_WRITE lights' unshadowed shading (chunks/area_term.glsl),
// a layer a light, added with the batch's weight (the mean over the view's first frames).
#include "chunks/lighting_common.glsl"

uniform float uLightCacheWeight;
// Light i's shading per unit radiance, times the weight; alpha the weight: the share of the
// pixel's cached positions that saw a surface. (Outputs take constant indices.)
layout(location = 0) out vec4 lightCache0;
layout(location = 1) out vec4 lightCache1;
layout(location = 2) out vec4 lightCache2;
layout(location = 3) out vec4 lightCache3;

void main() {
  lightCache0 = lightCache1 = lightCache2 = lightCache3 = vec4(0.0);  // unlit: no light
  vec3 v = viewDirection();
  SurfaceInputs s = readSurface(v);
  if (PN_UNLIT != 0 && uUnlit != 0) return;
  Layers L = surfaceLayers(s, v);
#define PN_CACHED_SHADING(i) \
  vec4(areaShading(areaLightOf(i), L) * uLightCacheWeight, uLightCacheWeight)
  lightCache0 = PN_CACHED_SHADING(0);
#if PN_LIGHT_CACHE_WRITE > 1
  lightCache1 = PN_CACHED_SHADING(1);
#endif
#if PN_LIGHT_CACHE_WRITE > 2
  lightCache2 = PN_CACHED_SHADING(2);
#endif
#if PN_LIGHT_CACHE_WRITE > 3
  lightCache3 = PN_CACHED_SHADING(3);
#endif
}
