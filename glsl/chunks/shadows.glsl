// Shadow maps of this frame's area-light samples: each is rendered from one point on the
// light's surface; a 2x2 hardware PCF lookup gives that sample's visibility.
// The maps are the layers of one depth texture array: one texture unit, and a layer index that
// may vary (an array of samplers could only be indexed with constants, through a branch per map).
uniform highp sampler2DArrayShadow uShadowMaps;
uniform mat4 uShadowMatrix[PN_MAX_SHADOW_MAPS];  // world -> shadow texture space [0, 1]^3
uniform vec4 uShadowParams[PN_MAX_SHADOW_MAPS];  // x: constant normal offset (world units), y: offset per
                                // unit of distance from the light (about 1.5 texel angles)

float sampleShadowMap(int index, vec3 coord) {
  return texture(uShadowMaps, vec4(coord.xy, float(index), coord.z));
}

// Point lights: cube maps rendered once per scene (passes/point_shadow_pass.h), compared
// against the depth the face's 90-degree projection gives the receiver. Only the variants with
// point-light cube maps have them: the branch alone costs llvmpipe about 5 % of an area-light
// frame.
#if PN_PUNCTUAL && PN_POINT_SHADOWS
uniform highp samplerCubeShadow uPointShadow0;
uniform highp samplerCubeShadow uPointShadow1;
uniform vec4 uPointShadowPos[PN_MAX_POINT_SHADOWS];     // xyz light position
uniform vec4 uPointShadowParams[PN_MAX_POINT_SHADOWS];  // near, far, offset, offset per distance
#if PN_MAX_POINT_SHADOWS != 2
#error "shadows.glsl samples exactly two point-light cube maps: update it with kMaxPointShadows"
#endif

float pointShadowVisibility(int index, vec3 worldPos, vec3 normal) {
  vec4 q = uPointShadowParams[index];
  vec3 light = uPointShadowPos[index].xyz;
  float dist = length(worldPos - light);
  vec3 v = worldPos + normal * (q.z + q.w * dist) - light;
  // The face is the major axis; its perspective depth, as the depth buffer stored it.
  float major = max(abs(v.x), max(abs(v.y), abs(v.z)));
  float n = q.x, f = q.y;
  float ndc = (f + n) / (f - n) - 2.0 * f * n / ((f - n) * max(major, n));
  vec4 c = vec4(v, ndc * 0.5 + 0.5);
  return index == 0 ? texture(uPointShadow0, c) : texture(uPointShadow1, c);
}
#endif

// The normal a shadow test offsets along: the interpolated one, turned toward the light where
// the surface passes light through to its other side (KHR_materials_diffuse_transmission), else
// a surface lit from behind would shadow itself.
vec3 shadowNormal(vec3 toLight) {
  vec3 n = normalize(vNormal);
#if PN_DIFFUSE_TRANSMISSION
  if (dot(n, toLight) < 0.0) n = -n;
#endif
  return n;
}

// index >= 0: shadow map `index`; -1: unshadowed. (Point lights' cube maps are looked up by
// chunks/punctual_term.glsl, only in the batches that have them: llvmpipe runs both sides of
// a branch, and the two cube lookups would run for every shadow test.)
float shadowVisibility(int index, vec3 worldPos, vec3 normal) {
  if (index < 0) return 1.0;
  // Normal-offset bias grows with the texel footprint, which grows with distance.
  float dist = max((uShadowMatrix[index] * vec4(worldPos, 1.0)).w, 0.0);
  vec3 p = worldPos + normal * (uShadowParams[index].x + uShadowParams[index].y * dist);
  vec4 c = uShadowMatrix[index] * vec4(p, 1.0);
  if (c.w <= 0.0) return 1.0;  // behind the light sample: nothing there to block
  vec3 s = c.xyz / c.w;
#ifdef PN_GROUND
  // The ground lies outside the scene's bounds, which the maps are fitted to: a point beyond
  // the far plane is behind whatever the map holds there (an empty texel keeps it lit).
  s.z = min(s.z, 1.0);
#endif
  if (any(lessThan(s, vec3(0.0))) || any(greaterThan(s, vec3(1.0)))) return 1.0;
  return sampleShadowMap(index, s);
}
