// Forward shading of one intermediate frame: split-sum environment light (with this frame's
// occlusion sample once the prepass exists), this frame's area-light samples (each weighted by
// the sample distributor and shadowed by its own shadow map), punctual lights and emission.
// Generated defines pick the variant (one table: passes/lighting_variant.h), so frame 1
// (environment only) runs a plain forward pass:
//   PN_OCCLUSION  progressive occlusion and screen-space indirect light
//   PN_AREA       area-light samples with shadow maps
//   PN_PUNCTUAL   KHR_lights_punctual lights
//   PN_CAPTURE    a probe's cube capture (passes/probe_volume.h): diffuse light only, alpha the
//                 signed distance to the probe
//   PN_PROBE_CACHE_WRITE  the per-view cache of the probe volume's lookups (passes/lighting_pass.h):
//                 no light, only what probeIrradiance() returns for the pixel, every few frames
//   PN_LIGHT_CACHE_WRITE  n > 0: the per-view cache of n area lights' unshadowed shading
//                 (passes/lighting_pass.h), a layer each, scaled by uLightCacheWeight
//   PN_LIGHT_CACHE  area-light samples read that cache instead of evaluating their light
//   PN_PROBES     the probe volume is on; PN_PROBE_CACHE: its per-view cache is read
//   PN_TRANSMISSION  1: a transmissive surface's own light (its diffuse base scaled by
//                 1 - transmission); 2: composes that light with what it transmits
//   PN_ACCUMULATE  the frame's only batch adds its sample straight to the running mean
//                 (chunks/accumulate.glsl), drawn into the other accumulation target
// shade() reads the surface (chunks/material.glsl), builds its layers (chunks/layers.glsl) and
// adds the terms: environment (below, with the occlusion samples and the probe volume), area
// lights (chunks/area_term.glsl), punctual lights (chunks/punctual_term.glsl), emission.
#include "chunks/brdf.glsl"
#include "chunks/material.glsl"
#include "chunks/environment.glsl"
#include "chunks/probe_volume.glsl"
#if PN_AREA
#include "chunks/area_lights.glsl"
#endif
#if PN_AREA || PN_PUNCTUAL
#include "chunks/shadows.glsl"
#endif
// (The composer includes a file once, where it first appears: one #if per file.)
#if PN_OCCLUSION || PN_TRANSMISSION == 2
#include "chunks/sampling.glsl"
#endif
#if PN_OCCLUSION
#include "chunks/occlusion.glsl"
#endif
#if PN_TRANSMISSION == 2
#include "chunks/transmission.glsl"
#endif
#if PN_ACCUMULATE
#include "chunks/accumulate.glsl"
uniform sampler2D uPrevious;  // the mean so far (the same texture as uAccumulated)
#endif

// Limits shared with the C++ side (passes/limits.h), given as generated defines.
const int MAX_AREA = PN_MAX_SHADOW_MAPS;  // area-light samples per pass: one shadow map each
const int MAX_PUNCTUAL = PN_MAX_PUNCTUAL_LIGHTS;

uniform vec4 uViewOrigin;  // (camera position, 1), or (direction to the viewer, 0) if orthographic
uniform float uEnvWeight;  // weight of the environment term in this frame (0 or 1)
// 1 where the surface's emission lights other surfaces (probe captures, screen-space indirect
// light); 0 on an area light's visible face, whose light the analytic area light already gives.
uniform float uIndirectEmission;

#if PN_CAPTURE
uniform int uSingleSided;  // the material is not double-sided: its back faces are walls' insides
uniform int uCaptureFaceSize;  // texels: face i is the square at x = i * size of the strip
flat in int vFace;
#endif

#if PN_PROBE_CACHE_WRITE
uniform mat4 uView;
layout(location = 0) out vec4 cacheIrradiance;  // rgb irradiance, a +-depth key (- : no probes)
layout(location = 1) out vec4 cacheRoom;        // the room's radiance toward r, and its share
layout(location = 2) out vec4 cacheWeights;     // three probes' weights and the key (occlusion_trace)
vec4 fragColor;                                 // unused here
#elif PN_LIGHT_CACHE_WRITE
uniform float uLightCacheWeight;
// Light i's shading per unit radiance, times the weight; alpha the weight: the share of the
// pixel's cached positions that saw a surface.
layout(location = 0) out vec4 lightCache0;
layout(location = 1) out vec4 lightCache1;
layout(location = 2) out vec4 lightCache2;
layout(location = 3) out vec4 lightCache3;
vec4 fragColor;  // unused here
#else
out vec4 fragColor;
#endif

#if PN_OCCLUSION
// This frame's diffuse occlusion rays, traced at a quarter of the pixels (occlusion_trace.frag):
// rgb the radiance a blocked ray found, alpha the traced pixel's linear depth (positive:
// blocked, negative: not, 0: background).
uniform sampler2D uOcclusion;
uniform int uOcclusionBlock;  // pixels a side of the blocks that trace one ray: 2, or 1
#endif

#if PN_OCCLUSION && PN_PROBE_CACHE
// The per-view cache: a still view's probe lookups change only as the volume fills, so they
// are made every few frames by the PN_PROBE_CACHE_WRITE variant and read back in between. The
// key (linear view depth over the volume's diagonal) finds the right texel where the frame's
// jittered sample lands on another surface than the cached one (silhouettes): of the pixel and
// its four neighbours, the best match. No lookup falls back to the probes: a software
// rasterizer runs both sides of a branch, so the fallback would cost every pixel.
// Layer 0: irradiance and the +-key; layer 1: the room's radiance and its share; layer 2: the
// first three probes' weights (the fourth: 1 - their sum) and the key again, for the occlusion
// rays.
uniform highp sampler2DArray uProbeCache;

void probeCacheRead(float key, float tolerance, out vec4 pv, out vec4 room) {
  ivec2 px = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(uProbeCache, 0).xy - 1;
  vec4 best = texelFetch(uProbeCache, ivec3(px, 0), 0);
  ivec2 bestPx = px;
  float bestError = abs(abs(best.a) - key);
  for (int i = 0; i < 4; ++i) {
    ivec2 q = clamp(px + (i == 0 ? ivec2(1, 0) : i == 1 ? ivec2(-1, 0) : i == 2 ? ivec2(0, 1)
                                                                              : ivec2(0, -1)),
                    ivec2(0), last);
    vec4 c = texelFetch(uProbeCache, ivec3(q, 0), 0);
    float e = abs(abs(c.a) - key);
    if (bestError > tolerance && e < bestError) {
      best = c;
      bestPx = q;
      bestError = e;
    }
  }
  pv = vec4(best.rgb, best.a > 0.0 ? 1.0 : 0.0);
  room = texelFetch(uProbeCache, ivec3(bestPx, 1), 0);
}
#endif

// The lighting terms, each in its chunk; shade() below calls them in turn.
#include "chunks/layers.glsl"
#if PN_AREA
#include "chunks/area_term.glsl"
#endif
#if PN_PUNCTUAL
#include "chunks/punctual_term.glsl"
#endif

#if PN_OCCLUSION || PN_PROBE_CACHE_WRITE
float probeCacheKey() {
  return -(uView * vec4(vWorldPos, 1.0)).z / uProbeDiagonal;
}
#endif

#if PN_OCCLUSION
// Set by shade() before any early return (they take derivatives): the probe cache's key and
// how far a jittered sample may move it, and the same for the occlusion rays' linear depth.
float gCacheKey, gCacheTolerance, gViewDepth, gRayTolerance;

// This frame's occlusion samples. Diffuse: where the ray hit, diffuseDelta is what it changes
// in the unoccluded irradiance (pi times the hit's radiance minus the unoccluded estimate's in
// that direction: occlusion_trace.frag). Specular: where the ray hit, its radiance replaces
// prefiltered (a broad lobe: set by environmentTerm from the irradiance).
void occlusionSamples(Layers L, out vec3 diffuseDelta, inout vec3 prefiltered,
                      out bool diffuseHit, out bool specularHit) {
  diffuseDelta = vec3(0.0);
  diffuseHit = false;
  specularHit = false;
  vec2 pixel = gl_FragCoord.xy;
  // Diffuse: one cosine-weighted direction, the ray of a 2x2 block (traced by one of its
  // pixels, a different one each frame), used where the traced pixel lies on this surface.
  // The block is one of those within a pixel of this one, chosen at random once per pixel:
  // its own block alone showed the early frames' noise, and a ray's firefly, as 2x2 squares;
  // another one each frame mixed the blocks' sequences, and the image converged like white
  // noise. Where the traced pixel lies on another surface, the own block's ray is taken if its
  // pixel does not; failing both (a silhouette) the unoccluded estimate stands.
  ivec2 own = ivec2(gl_FragCoord.xy) / uOcclusionBlock;
  ivec2 offset = (ivec2(floor(hash2(pixel, 8u) * 3.0)) - 1) * (uOcclusionBlock - 1);
  ivec2 pick = (ivec2(gl_FragCoord.xy) + offset) / uOcclusionBlock;
  vec4 ray = texelFetch(uOcclusion, clamp(pick, ivec2(0), textureSize(uOcclusion, 0) - 1), 0);
  vec4 ownRay = texelFetch(uOcclusion, own, 0);
  if (abs(abs(ray.a) - gViewDepth) >= gRayTolerance) ray = ownRay;
  // A miss's correction is zero unless the early frames' filter (occlusion_filter.frag) mixed
  // its neighbours' into it: added either way, on this surface.
  if (abs(abs(ray.a) - gViewDepth) < gRayTolerance) {
    diffuseDelta = ray.rgb * PI;
    diffuseHit = ray.a > 0.0;
  }
#if PN_BROAD_LOBE
  // A dielectric's broad specular lobe (gpu_scene.h materialFeatures) is occluded like the
  // diffuse one: a second march would cost as much for a few per cent of the light.
  specularHit = diffuseHit;
#else
  // Specular: one GGX half vector, reflected, marched here.
  vec3 hit;
  vec3 h = tangentFrame(L.n) * sampleGgxHalfVector(pixelSample(pixel, 1.0), L.alpha);
  vec3 sDir = reflect(-L.v, h);
  if (dot(sDir, L.n) > 0.0 &&
      traceOcclusion(vWorldPos, sDir, fract(uSequence.y * 5.0 + hash2(pixel, 6u).x), hit)) {
    prefiltered = hit;
    specularHit = true;
  }
#endif
}
#endif

#if PN_DIFFUSE_TRANSMISSION
// KHR_materials_diffuse_transmission: the irradiance arriving at the surface's other side:
// the probe volume's where it answers (looked up for -n; the per-view probe cache holds only
// the front's), else the environment's.
vec3 backIrradiance(Layers L) {
  vec3 e = envIrradiance(-L.n);
#if !(PN_OCCLUSION && PN_PROBE_CACHE)
  if (PN_PROBES != 0) {
    vec4 room;
    vec4 pv = probeIrradiance(vWorldPos, -L.n, L.v, -L.n, false, room);
    e = mix(e, pv.rgb, pv.a);
  }
#endif
  return e;
}
#endif

// The environment's light (split sum), with this frame's occlusion samples and the probe
// volume's answer where they have one. skyLossWeight: 1 while the diffuse term is the
// unoccluded E(n), which a sky-shadow sample corrects later; 0 once a ray or the probes
// replaced it.
vec3 environmentTerm(Layers L, float occlusion, inout float skyLossWeight) {
  vec3 irradiance = envIrradiance(L.n);
  vec3 r = specularReflection(L.v, L.n);
  vec3 prefiltered = envRadiance(r, L.perceptualRoughness);
  bool diffuseHit = false, specularHit = false;
  vec3 diffuseDelta = vec3(0.0);
#if PN_OCCLUSION
  occlusionSamples(L, diffuseDelta, prefiltered, diffuseHit, specularHit);
  if (diffuseHit) skyLossWeight = 0.0;
#endif
  // The probe volume answers what the screen-space rays did not: the environment's light and
  // every bounce, with the visibility the probes saw (which also stands in for the sky-shadow
  // correction). A diffuse ray's hit corrects it for its one direction (diffuseDelta).
  // Frame 1 (no occlusion) keeps the sky's reflection: it is the frame shown while the view
  // moves, and one frame of a long mean. Elsewhere only surfaces whose specular layer shows
  // enough of the room (reflectance times smoothness) pay for the radiance lookup.
#if PN_OCCLUSION
  float showsRoom = max(L.specularScale.r, max(L.specularScale.g, L.specularScale.b)) *
                    (1.0 - L.perceptualRoughness);
  bool glossy = showsRoom > 0.01 && !specularHit;
#else
  bool glossy = false;
#endif
  vec4 room = vec4(0.0);
  vec4 pv = vec4(0.0);
#if PN_OCCLUSION && PN_PROBE_CACHE
  probeCacheRead(gCacheKey, gCacheTolerance, pv, room);
#else
  if (PN_PROBES != 0) {
    pv = probeIrradiance(vWorldPos, L.n, L.v, r, glossy, room);
  }
#endif
  if (PN_PROBES != 0) {
#if PN_CAPTURE
    // Captures build on what the volume holds, nothing else: each adds a bounce (the usable
    // probes' answer alone; the environment's share would light an enclosed room's first
    // captures with the unoccluded sky).
    irradiance = pv.rgb;
#else
    if (pv.a > 1e-3) {
      // The environment's share by trust (the cache holds the mix already, alpha 1).
      irradiance = mix(irradiance, pv.rgb, pv.a);
      // Glossy reflections of the room: where the probes see geometry toward r, their
      // radiance replaces the sky's, blurred toward the cosine-weighted mean (E / pi) as the
      // surface gets rough (the probes' maps have no mip chain).
      if (glossy) {
        vec3 roomRadiance = mix(room.rgb, pv.rgb * INV_PI, L.perceptualRoughness);
        prefiltered = mix(prefiltered, roomRadiance, room.a);
      }
      skyLossWeight = 0.0;
    }
#endif
  }
  // This frame's diffuse ray: the share of its direction in the estimate, replaced by what the
  // ray found. A sample may go below zero (a dark hit where the estimate is bright) and is kept
  // so: clamping it here added 1 % to the Cornell box's mean. Only the read-outs clamp the
  // running mean (Renderer::readRadiance; the tone mapping).
  irradiance += diffuseDelta;
#if PN_OCCLUSION && PN_BROAD_LOBE
  if (diffuseHit) prefiltered = irradiance * INV_PI;
#endif
  // The broad sheen lobe reflects the cosine-weighted environment (with this frame's
  // occlusion sample), scaled by its albedo: exact in a white furnace.
  vec3 color = occlusion * L.baseScale *
               (L.sheenScale * (L.diffuseColor * irradiance * INV_PI +
                                prefiltered * L.specularScale) +
                L.sheenColor * (L.sheenE * INV_PI) * irradiance);
#if PN_DIFFUSE_TRANSMISSION
  // Diffuse transmission: the light arriving at the other side (no occlusion sample there).
  color += L.baseScale * L.sheenScale * L.backColor * backIrradiance(L) * INV_PI;
#endif
  if (L.coat > 0.0) {
    vec3 coatDfg = dfg(L.coatNoV, L.coatRoughness);
    vec3 coatPrefiltered = envRadiance(reflect(-L.v, L.coatN), L.coatRoughness);
    color += occlusion * L.coat * coatPrefiltered * (0.04 * coatDfg.x + coatDfg.y);
  }
  return uEnvWeight * color;
}

#if PN_PROBE_CACHE_WRITE
// The per-view probe cache's texels: the same lookup the shading makes (the room's radiance
// wherever the specular layer shows enough of it: whether this frame's specular ray hits is
// decided when reading).
void writeProbeCache(Layers L) {
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
#endif

#if PN_LIGHT_CACHE_WRITE
// The per-view area-light cache: one layer a light (PN_LIGHT_CACHE_WRITE of them; outputs take
// constant indices).
void writeLightCache(Layers L) {
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
#endif

// The frame's sample at this pixel into fragColor: the surface's layers, then each term
// (environment, area lights, punctual lights, emission), or one of the variants' other outputs.
void shade() {
  vec3 v = normalize(uViewOrigin.xyz - vWorldPos * uViewOrigin.w);
#if PN_OCCLUSION
  // Derivatives before any early return. A jitter moves the sample by under a pixel in x and
  // y: the key changes by at most fwidth, plus half-float rounding.
  gCacheKey = probeCacheKey();
  gCacheTolerance = 2.0 * fwidth(gCacheKey) + 2e-3 * gCacheKey;
  // The same for the occlusion ray taken from a nearby 2x2 block (occlusion_trace.frag),
  // traced up to two pixels away in x and y (plus the jitter) on the prepass's half floats.
  gViewDepth = -(uView * vec4(vWorldPos, 1.0)).z;
  gRayTolerance = 2.0 * fwidth(gViewDepth) + 2e-3 * gViewDepth;
#endif
#if PN_PROBE_CACHE_WRITE
  cacheIrradiance = vec4(0.0);
  cacheRoom = vec4(0.0);
  cacheWeights = vec4(0.0);
#endif
#if PN_LIGHT_CACHE_WRITE
  lightCache0 = lightCache1 = lightCache2 = lightCache3 = vec4(0.0);  // unlit: no light
#endif
#if PN_CAPTURE
  if (int(gl_FragCoord.x) / uCaptureFaceSize != vFace) discard;  // another face's square
  // What the probe sees, and how far (in the volume's diagonals; back faces negative, black:
  // a probe that sees mostly those is buried in geometry).
  float probeDistance = length(uViewOrigin.xyz - vWorldPos) / uProbeDiagonal;
  if (!gl_FrontFacing && uSingleSided != 0) {
    fragColor = vec4(0.0, 0.0, 0.0, -probeDistance * uEnvWeight);
    return;
  }
#endif
  SurfaceInputs s = readSurface(v);
  if (PN_UNLIT != 0 && uUnlit != 0) {
    // KHR_materials_unlit: the base colour is the radiance (once, in the first batch).
    fragColor = vec4(s.baseColor.rgb * uEnvWeight,
                     uEnvWeight * (uAlphaMode == 2 && uCoverageFrame < 0 ? s.baseColor.a : 1.0));
#if PN_CAPTURE
    fragColor.a = probeDistance * uEnvWeight;
#endif
    return;
  }
  Layers L = surfaceLayers(s, v);
#if PN_PROBE_CACHE_WRITE
  writeProbeCache(L);
  return;
#endif
#if PN_LIGHT_CACHE_WRITE
  writeLightCache(L);
  return;
#endif
#if PN_TRANSMISSION == 2
  // Under the coat and the sheen like the base; the surface's own light was drawn per batch.
  // A smooth surface (at the shading's roughness floor) transmits without scattering: GGX's
  // long tail at that floor would still throw a few samples pixels away.
  float transmitAlpha = s.perceptualRoughness > MIN_PERCEPTUAL_ROUGHNESS ? L.alpha : 0.0;
  vec3 own = texelFetch(uGlassLight, ivec2(gl_FragCoord.xy), 0).rgb;
  fragColor = vec4(own + L.baseScale * L.sheenScale * L.transmitColor *
                             transmittedRadiance(vWorldPos, L.n, v, transmitAlpha, uIor),
                   1.0);
  return;
#endif

  vec3 color = vec3(0.0);
  float skyLossWeight = 1.0;
  if (uEnvWeight > 0.0) color += environmentTerm(L, s.occlusion, skyLossWeight);
#if PN_AREA
  color += areaTerm(L);
#endif
#if PN_PUNCTUAL
  color += punctualTerm(L, s.occlusion, skyLossWeight);
#endif
#if PN_CAPTURE
  // Emissive surfaces light the probes (once, in the first batch), but for the area lights'
  // visible faces: their light is the area lights'.
  fragColor = vec4(color + s.emissive * (uEnvWeight * uIndirectEmission),
                   probeDistance * uEnvWeight);
  return;
#endif
  color += s.emissive * uEnvWeight;
  // Alpha marks what screen-space indirect light may reuse: an area light's visible face is
  // excluded (its light is already counted by the analytic area light), and extra light batches
  // add nothing. Alpha-blended BLEND surfaces (frame 1) put their coverage there for the blend
  // instead.
  float reusable =
      uIndirectEmission > 0.5 || max(s.emissive.r, max(s.emissive.g, s.emissive.b)) <= 0.0 ? 1.0
                                                                                           : 0.0;
  bool blended = uAlphaMode == 2 && uCoverageFrame < 0;
  fragColor = vec4(color, uEnvWeight * (blended ? s.baseColor.a : reusable));
}

void main() {
  shade();
#if PN_ACCUMULATE
  fragColor = runningMean(texelFetch(uPrevious, ivec2(gl_FragCoord.xy), 0), fragColor);
#endif
}
