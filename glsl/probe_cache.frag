// The per-view cache of the probe volume's lookups (passes/lighting_pass.h), written every few
// frames where the frame's depth pass left the surfaces: no light, only what probeIrradiance()
// returns for the pixel (the room's radiance wherever the specular layer shows enough of it;
// whether a frame's specular ray hits is decided when reading, chunks/environment_term.glsl).
uniform mat4 uView;
#include "chunks/lighting_common.glsl"

layout(location = 0) out vec4 cacheIrradiance;  // rgb irradiance, a +-depth key (- : no probes)
layout(location = 1) out vec4 cacheRoom;        // the room's radiance toward r, and its share
layout(location = 2) out vec4 cacheWeights;     // three probes' weights and the key (occlusion_trace)

void main() {
  cacheIrradiance = vec4(0.0);
  cacheRoom = vec4(0.0);
  cacheWeights = vec4(0.0);
  vec3 v = viewDirection();
  SurfaceInputs s = readSurface(v);
  if (PN_UNLIT != 0 && uUnlit != 0) return;
  Layers L = surfaceLayers(s, v);
  float showsRoom = max(L.specularScale.r, max(L.specularScale.g, L.specularScale.b)) *
                    (1.0 - L.perceptualRoughness);
  vec4 room, weights;
  vec4 pv = probeIrradianceWeights(vWorldPos, L.n, L.v, specularReflection(L.v, L.n),
                                   showsRoom > 0.01, room, weights);
  float key = probeCacheKey();
  cacheIrradiance = vec4(mix(envIrradiance(L.n), pv.rgb, pv.a), pv.a > 1e-3 ? key : -key);
  cacheRoom = room;
  cacheWeights = vec4(pv.a > 1e-3 ? weights.xyz : vec3(0.0), cacheIrradiance.a);
}
