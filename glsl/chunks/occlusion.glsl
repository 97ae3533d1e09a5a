// Progressive screen-space occlusion (Otto et al. 2020, section 3.2): each frame tests one
// BRDF-sampled direction per pixel against the depth prepass. A hit drops that direction's
// environment light; with screen-space indirect on, it adds the radiance already accumulated
// at the hit instead (one bounce, as the paper's public demo does).
uniform bool uIndirectEnabled;
uniform float uIndirectClamp;  // largest radiance (max over RGB) one sample brings back
uniform sampler2D uPrepass;      // xyz view-space normal, w linear depth (0 = background)
uniform sampler2D uAccumulated;  // running mean so far (linear radiance)
uniform float uOcclusionDistance;
uniform mat4 uView;
uniform mat4 uProjection;  // unjittered
uniform vec2 uViewportSize;

const int OCCLUSION_STEPS = 4;

// Marches from world point p along unit direction d up to uOcclusionDistance, at steps
// jittered per frame (so over the frames the march covers the whole segment). Returns true on
// a hit and the radiance found there (when indirect light is on). Written without early exits
// so the loop unrolls into straight-line code: a SIMD software rasterizer runs every lane
// through every branch anyway, and divergent returns only add mask bookkeeping.
bool traceOcclusion(vec3 p, vec3 d, float jitter, out vec3 hitRadiance) {
  hitRadiance = vec3(0.0);
  vec3 vp = (uView * vec4(p, 1.0)).xyz;
  vec3 vd = mat3(uView) * d;
  // Clip-space position is linear in t: project the start and the direction once.
  vec4 c0 = uProjection * vec4(vp, 1.0);
  vec4 c1 = uProjection * vec4(vd, 0.0);
  float stepLength = uOcclusionDistance / float(OCCLUSION_STEPS);
  // A sample that lands in the starting pixel compares the ray with the depth of the very
  // surface it leaves, which only measures depth-buffer discretisation: skip it.
  ivec2 size = ivec2(uViewportSize);
  ivec2 origin = ivec2((c0.xy / c0.w * 0.5 + 0.5) * uViewportSize);
  bool done = false;  // hit, or the ray left the screen or passed behind the camera
  bool hit = false;
  vec2 hitUv = vec2(0.0);
  for (int i = 0; i < OCCLUSION_STEPS; ++i) {
    float t = stepLength * (float(i) + jitter);
    vec4 clip = c0 + c1 * t;
    float rayDepth = -(vp.z + vd.z * t);  // linear view depth, as the prepass stores it
    vec2 uv = clip.xy / max(clip.w, 1e-4) * 0.5 + 0.5;
    // Once off screen or behind the camera a ray stays there: the march ends.
    done = done || rayDepth <= 1e-4 || any(lessThan(uv, vec2(0.0))) ||
           any(greaterThan(uv, vec2(1.0)));
    ivec2 texel = clamp(ivec2(uv * uViewportSize), ivec2(0), size - 1);
    vec4 g = texelFetch(uPrepass, texel, 0);
    float sceneDepth = g.w;
    // Occluded when the ray is behind the visible surface, but not by more than the trace
    // length (a thin-object guess: farther surfaces are assumed not to block), and when that
    // surface faces the ray: passing behind a surface that faces away from it means the ray
    // is behind the object, where the depth buffer knows nothing.
    bool occluded = !done && texel != origin && sceneDepth > 0.0 &&
                    rayDepth > sceneDepth + 0.002 * rayDepth &&
                    rayDepth - sceneDepth < uOcclusionDistance && dot(g.xyz, -vd) > 0.0;
    hitUv = occluded ? uv : hitUv;
    hit = hit || occluded;
    done = done || occluded;
  }
  if (hit && uIndirectEnabled) {
    // The hit pixel itself, not a filtered mix: a mix with a lamp's face (alpha 0, radiance in
    // the hundreds) brought back a share of the lamp, one clamped speckle per such ray. The
    // same holds for the pixels on the face's edge, which the jittered frames cover partly: only
    // a pixel that is (almost) all reusable surface is reused, fading out below alpha 0.9.
    ivec2 hitTexel = clamp(ivec2(hitUv * uViewportSize), ivec2(0), size - 1);
    vec4 acc = texelFetch(uAccumulated, hitTexel, 0);
    hitRadiance = max(acc.rgb, vec3(0.0)) * saturate(acc.a) * saturate(10.0 * acc.a - 9.0);
    // Clamped like a path tracer's indirect samples: scaled so no channel exceeds the limit.
    float peak = max(hitRadiance.r, max(hitRadiance.g, hitRadiance.b));
    if (peak > uIndirectClamp) hitRadiance *= uIndirectClamp / peak;
  }
  return hit;
}
