// This frame's diffuse occlusion rays at a quarter of the pixels (passes/occlusion_pass.h):
// texel (i, j) traces the ray of pixel b (i, j) + uBlockOffset of the full image (block size
// b = uBlock: 2, or 1 where every pixel traces its own), from the
// prepass's position and normal, with the cosine-weighted direction and march jitter that
// pixel's sequence gives. Output: where the ray was blocked, the radiance found there
// (screen-space indirect light) minus the radiance the unoccluded estimate has in that direction,
// and in alpha the pixel's linear depth, positive where the ray was blocked, negative where it
// was not (0: background), so the lighting pass can tell whether the ray left its own surface.
//
// Why the difference: the lighting pass adds pi times it to the unoccluded irradiance (the probe
// volume's where it answers, else the environment's). A hit then replaces only its own
// direction's share, and a miss keeps the estimate of every direction the screen cannot see.
// Replacing the whole irradiance by pi L(hit) on a hit and crediting a miss with all of it gave
// misses the light of the (near, lit) directions that hit: the Cornell box gained 2-3 % over the
// radiosity balance and kept brightening with frames (docs/decisions/
// 2026-11-28-screen-space-control-variate.md).
#include "chunks/sampling.glsl"
#include "chunks/occlusion.glsl"
#include "chunks/environment.glsl"
#if PN_PROBES
#include "chunks/probe_volume.glsl"
#endif
#if PN_PROBE_CACHE
// The lighting pass's per-view probe cache, made in an earlier frame of this view: layer 2
// holds the first three of the four probes' weights at that texel's surface and the +-key
// (linear view depth over the volume's diagonal; - : no probe answered).
uniform highp sampler2DArray uProbeCache;

// Whether the cache's texel holds the surface the prepass has at its pixel (linear view depth
// `depth`): the cache was drawn at a jittered sample, so a silhouette's texel may hold the
// other side. A relative tolerance: a jitter of under a pixel moves the depth of all but the
// most grazing surfaces by far less, and a contact's two sides have nearly the same weights.
bool cacheHoldsSurface(float depth, float cachedKey) {
  return abs(abs(cachedKey) * uProbeDiagonal - depth) <= 0.03 * depth;
}
#endif
uniform mat4 uInvView;
uniform mat4 uInvProjection;  // unjittered, as the prepass
uniform vec4 uViewOrigin;     // as the lighting pass's: (camera position, 1), or (to the viewer, 0)
uniform int uBlock;           // 2: a ray per 2x2 block, 1: per pixel
uniform vec2 uBlockOffset;    // which pixel of each block traces this frame
out vec4 fragColor;
void main() {
  ivec2 size = ivec2(uViewportSize);
  ivec2 px = min(ivec2(gl_FragCoord.xy) * uBlock + ivec2(uBlockOffset), size - 1);
  vec4 g = texelFetch(uPrepass, px, 0);
  if (g.w <= 0.0) {
    fragColor = vec4(0.0);
    return;
  }
  // The view-space point at that depth on the pixel centre's ray, through two of its points
  // (the near plane and NDC depth 0: finite with an infinite far plane too), so perspective
  // and orthographic alike.
  vec2 pixel = vec2(px) + 0.5;
  vec2 ndc = pixel / uViewportSize * 2.0 - 1.0;
  vec4 a = uInvProjection * vec4(ndc, -1.0, 1.0);
  vec4 b = uInvProjection * vec4(ndc, 0.0, 1.0);
  a.xyz /= a.w;
  b.xyz /= b.w;
  vec3 viewPos = mix(a.xyz, b.xyz, (-g.w - a.z) / (b.z - a.z));
  vec3 p = (uInvView * vec4(viewPos, 1.0)).xyz;
  vec3 n = normalize(mat3(uInvView) * g.xyz);
  // The block's own sample sequence (its texel here): each pixel takes its rays from one block
  // (lighting.frag), so over the frames its directions are the block's low-discrepancy
  // sequence, as stratified as a pixel's own would be.
  vec2 block = gl_FragCoord.xy;
  vec3 dir = tangentFrame(n) * sampleCosineHemisphere(pixelSample(block, 0.0));
  vec3 hit;
  bool blocked = traceOcclusion(p, dir, fract(uSequence.x * 7.0 + hash2(block, 5u).x), hit);
  vec3 unoccluded = vec3(0.0);
  bool probesAnswer = false;
  bool sameSurface = true;
  if (blocked) {
    // The environment's radiance toward dir, a little blurred (a few texels of the sky, not the
    // sun's one), unless the probes answer: the radiance their maps hold toward dir, with the
    // weights of the irradiance the lighting pass looks up at this point.
#if PN_PROBES
    vec3 v = normalize(uViewOrigin.xyz - p * uViewOrigin.w);  // the lighting pass's v
#if PN_PROBE_CACHE
    // The weights the cache holds, which its irradiance was made with: the same estimate in
    // expectation, for one radiance fetch (probeRadianceDrawn). Where the texel holds another
    // surface, the ray changes nothing: the pixel keeps the probes' estimate.
    vec4 cached = texelFetch(uProbeCache, ivec3(px, 2), 0);
    sameSurface = cacheHoldsSurface(g.w, cached.a);
    vec4 pv = probeRadianceDrawn(p, n, v, dir, cached.xyz, cached.a > 0.0 ? 1.0 : 0.0,
                                 fract(uSequence.y * 11.0 + hash2(block, 9u).y));
#else
    vec4 pv = probeRadianceToward(p, n, v, dir);
#endif
    probesAnswer = pv.a > 1e-3;
    // The unusable probes' share stands for the environment (probeRadianceToward).
    unoccluded = pv.a < 0.999 ? mix(envRadiance(dir, 0.5), pv.rgb, pv.a) : pv.rgb;
#else
    unoccluded = envRadiance(dir, 0.5);
#endif
    // Clamped like the hit's radiance: a sun behind a blocker must not bring back a huge
    // negative sample.
    float peak = max(unoccluded.r, max(unoccluded.g, unoccluded.b));
    if (peak > uIndirectClamp) unoccluded *= uIndirectClamp / peak;
    // Without screen-space indirect light a hit finds nothing to bring back, but the probes
    // already saw the blocker: their answer stands (no second occlusion of their light).
    if (probesAnswer && !uIndirectEnabled) hit = unoccluded;
    if (!sameSurface) hit = unoccluded;
  }
  fragColor = vec4(hit - unoccluded, blocked ? g.w : -g.w);
}
