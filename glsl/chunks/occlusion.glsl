// Progressive screen-space occlusion (Otto et al. 2020, section 3.2): each frame tests one
// BRDF-sampled direction per pixel against the depth prepass. A hit drops that direction's
// environment light; with screen-space indirect on, it adds the radiance already accumulated
// at the hit instead (one bounce, as the paper's public demo does).
uniform bool uIndirectEnabled;
uniform sampler2D uPrepass;      // xyz view-space normal, w linear depth (0 = background)
uniform sampler2D uAccumulated;  // running mean so far (linear radiance)
uniform float uOcclusionDistance;
uniform mat4 uView;
uniform mat4 uProjection;  // unjittered
uniform vec2 uViewportSize;

const int OCCLUSION_STEPS = 6;

// Marches from world point p along unit direction d up to uOcclusionDistance. Returns true
// on a hit and the radiance found there (when indirect light is on).
bool traceOcclusion(vec3 p, vec3 d, float jitter, out vec3 hitRadiance) {
  hitRadiance = vec3(0.0);
  vec3 vp = (uView * vec4(p, 1.0)).xyz;
  vec3 vd = mat3(uView) * d;
  for (int i = 0; i < OCCLUSION_STEPS; ++i) {
    float t = uOcclusionDistance * (float(i) + jitter) / float(OCCLUSION_STEPS);
    vec3 q = vp + vd * t;
    if (q.z >= -1e-4) return false;  // behind the camera
    vec4 clip = uProjection * vec4(q, 1.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return false;
    vec4 g = texelFetch(uPrepass, ivec2(uv * uViewportSize), 0);
    float sceneDepth = g.w;
    float rayDepth = -q.z;
    // Occluded when the ray is behind the visible surface, but not by more than the trace
    // length (a thin-object guess: farther surfaces are assumed not to block).
    if (sceneDepth > 0.0 && rayDepth > sceneDepth + 0.002 * rayDepth &&
        rayDepth - sceneDepth < uOcclusionDistance) {
      if (uIndirectEnabled) {
        // Only surfaces that face the shading point send light back toward it.
        float facing = dot(g.xyz, -vd);
        vec4 acc = texture(uAccumulated, uv);
        hitRadiance = facing > 0.0 ? acc.rgb * saturate(acc.a) : vec3(0.0);
      }
      return true;
    }
  }
  return false;
}
