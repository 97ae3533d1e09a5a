// Forward shading of one intermediate frame: split-sum environment light (with this frame's
// occlusion sample once the prepass exists), this frame's area-light samples (each weighted by
// the sample distributor and shadowed by its own shadow map), punctual lights and emission.
// Generated defines pick the variant, so frame 1 (environment only) runs a plain forward pass:
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

// The batch's samples: PN_AREA_COUNT area-light samples, sorted by light (bit i of
// PN_AREA_STARTS: sample i's light is not sample i - 1's), and PN_PUNCTUAL_COUNT punctual ones.
// Loops over them run to these constants and unroll, so arrays are read at constant indices.
uniform vec3 uAreaPos[MAX_AREA];
uniform vec3 uAreaDir[MAX_AREA];
uniform vec3 uAreaRight[MAX_AREA];
uniform vec3 uAreaUp[MAX_AREA];
uniform vec4 uAreaShape[MAX_AREA];     // width, height, 1 = disk, shadow map index (-1 none)
uniform vec3 uAreaRadiance[MAX_AREA];  // colour * luminance * sample weight

uniform vec4 uPunctualPos[MAX_PUNCTUAL];    // xyz, w: 0 point, 1 spot, 2 directional
uniform vec4 uPunctualDir[MAX_PUNCTUAL];    // xyz direction of travel, w: range (0 = none)
uniform vec3 uPunctualColor[MAX_PUNCTUAL];  // colour * intensity * weight
uniform vec2 uPunctualCone[MAX_PUNCTUAL];   // spot: scale, offset (KHR_lights_punctual)
uniform int uPunctualShadow[MAX_PUNCTUAL];  // shadow map of this sample (-1: unshadowed)
uniform vec4 uPunctualDisk[MAX_PUNCTUAL];   // directional: xyz centre direction of travel,
                                            // w tan(angular radius); 0 for the others

#if PN_CAPTURE
uniform int uSingleSided;  // the material is not double-sided: its back faces are walls' insides
uniform int uCaptureFaceSize;  // texels: face i is the square at x = i * size of the strip
flat in int vFace;
#endif

#if PN_PROBE_CACHE_WRITE
uniform mat4 uView;
layout(location = 0) out vec4 cacheIrradiance;  // rgb irradiance, a +-depth key (- : no probes)
layout(location = 1) out vec4 cacheRoom;        // the room's radiance toward r, and its share
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
// Layer 0: irradiance and the +-key; layer 1: the room's radiance and its share.
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

#if PN_LIGHT_CACHE
// The area lights' per-view cache: a light's unshadowed shading, the mean over the view's
// first jittered frames, so only the samples' shadow tests remain per frame. Its mean over the
// pixel stands in for the shading at this frame's sub-pixel position: exact wherever the
// pixel's samples agree on visibility, a ratio estimate (Heitz et al. 2018) at silhouettes.
uniform highp sampler2DArray uLightCache;
uniform int uAreaLayer[MAX_AREA];  // the cache layer of each sample's light
#endif

#if PN_AREA
AreaLight areaLightOf(int i) {
  AreaLight L;
  L.position = uAreaPos[i];
  L.direction = uAreaDir[i];
  L.right = uAreaRight[i];
  L.up = uAreaUp[i];
  L.size = uAreaShape[i].xy;
  L.disk = uAreaShape[i].z > 0.5;
  return L;
}

// Light L's unshadowed shading at the pixel per unit radiance: what each of its samples
// multiplies by its shadow-map visibility.
vec3 areaShading(AreaLight L, vec3 n, vec3 v, vec3 f0, float f90, float alpha,
                 vec3 diffuseColor, float baseScale, float sheenScale, vec3 sheenColor,
                 float sheenA, float coat, vec3 coatN, float coatAlpha) {
  float irradiance;
  vec3 specular;
  evaluateAreaLight(L, vWorldPos, n, v, f0, f90, alpha, irradiance, specular);
  // Sheen: its lobe is broad, so the light's irradiance times the lobe's value D V toward the
  // light's centre (irradiance already holds the cosine).
  float sheenLight = 0.0;
  if (max(sheenColor.r, max(sheenColor.g, sheenColor.b)) > 0.0 && irradiance > 0.0) {
    vec3 lc = normalize(L.position - vWorldPos);
    float NoLc = dot(n, lc);
    sheenLight = NoLc > 0.0 ? sheenBrdfCos(n, v, lc, sheenA) / NoLc : 0.0;
  }
  vec3 coatSpecular = vec3(0.0);
  if (coat > 0.0) {
    float coatIrradiance;
    evaluateAreaLight(L, vWorldPos, coatN, v, vec3(0.04), 1.0, coatAlpha, coatIrradiance,
                      coatSpecular);
  }
  return baseScale * (sheenScale * (diffuseColor * irradiance * INV_PI + specular) +
                      sheenColor * (sheenLight * irradiance)) +
         coat * coatSpecular;
}
#endif

#if PN_OCCLUSION || PN_PROBE_CACHE_WRITE
float probeCacheKey() {
  return -(uView * vec4(vWorldPos, 1.0)).z / uProbeDiagonal;
}
#endif

#if PN_PUNCTUAL
// The specular lobe of a punctual sample: only the forms this batch's kinds need.
vec3 punctualLobe(vec3 n, vec3 v, vec3 l, vec3 f0, float f90, float alpha, vec4 disk) {
#if (PN_PUNCTUAL_KINDS & 4) == 0
  return specularBrdf(n, v, l, f0, f90, alpha, 1.0) * max(dot(n, l), 0.0);
#elif (PN_PUNCTUAL_KINDS & 11) == 0
  return diskSpecular(n, v, f0, f90, alpha, disk);
#else
  return punctualSpecular(n, v, l, f0, f90, alpha, disk);
#endif
}
#endif

// The frame's sample at this pixel into fragColor.
void shade() {
  vec3 v = normalize(uViewOrigin.xyz - vWorldPos * uViewOrigin.w);
#if PN_OCCLUSION
  // Derivatives before any early return. A jitter moves the sample by under a pixel in x and
  // y: the key changes by at most fwidth, plus half-float rounding.
  float cacheKey = probeCacheKey();
  float cacheTolerance = 2.0 * fwidth(cacheKey) + 2e-3 * cacheKey;
  // The same for the occlusion ray taken from a nearby 2x2 block (occlusion_trace.frag),
  // traced up to two pixels away in x and y (plus the jitter) on the prepass's half floats.
  float viewDepth = -(uView * vec4(vWorldPos, 1.0)).z;
  float rayTolerance = 2.0 * fwidth(viewDepth) + 2e-3 * viewDepth;
#endif
#if PN_PROBE_CACHE_WRITE
  cacheIrradiance = vec4(0.0);
  cacheRoom = vec4(0.0);
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
  vec3 n = s.normal;
  float NoV = max(dot(n, v), 1e-4);
  if (PN_UNLIT != 0 && uUnlit != 0) {
    // KHR_materials_unlit: the base colour is the radiance (once, in the first batch).
    fragColor = vec4(s.baseColor.rgb * uEnvWeight,
                     uEnvWeight * (uAlphaMode == 2 && uCoverageFrame < 0 ? s.baseColor.a : 1.0));
#if PN_CAPTURE
    fragColor.a = probeDistance * uEnvWeight;
#endif
    return;
  }
  vec3 diffuseColor = s.baseColor.rgb * (1.0 - s.metallic);
  vec3 f0 = mix(uDielectricF0, s.baseColor.rgb, s.metallic);
  float f90 = mix(uDielectricF90, 1.0, s.metallic);
  float alpha = s.perceptualRoughness * s.perceptualRoughness;
  vec3 dfgTerms = dfg(NoV, s.perceptualRoughness);
  vec3 specularScale = (f0 * dfgTerms.x + f90 * dfgTerms.y) * (1.0 + f0 * (1.0 / dfgTerms.z - 1.0));
  // glTF's fresnel_mix: the diffuse base only receives what the specular layer does not
  // reflect (albedo scaling with the directional specular albedo), so a white dielectric in a
  // white furnace reflects exactly the environment.
  diffuseColor *= vec3(1.0) - specularScale;
#if PN_TRANSMISSION
  // KHR_materials_transmission: of what the specular layer lets through, the share
  // `transmission` passes through the surface (tinted by the base colour) instead of being
  // diffused; it is added where the surfaces are composed (PN_TRANSMISSION 2).
  vec3 transmitColor = diffuseColor * uTransmission;
  diffuseColor -= transmitColor;
#endif
#if PN_CAPTURE
  // Probes store irradiance, so light leaves a captured surface view-independently: the
  // specular layer's directional albedo is reflected as if diffuse (energy kept, metals not
  // black), and no specular lobe is evaluated.
  diffuseColor += specularScale;
  f0 = vec3(0.0);
  f90 = 0.0;
  specularScale = vec3(0.0);
#endif
#if PN_PROBE_CACHE_WRITE
  {
    // The same lookup the shading below makes (the room's radiance wherever the specular layer
    // shows enough of it: whether this frame's specular ray hits is decided when reading).
    float showsRoom = max(specularScale.r, max(specularScale.g, specularScale.b)) *
                      (1.0 - s.perceptualRoughness);
    vec4 room;
    vec4 pv = probeIrradiance(vWorldPos, n, v, reflect(-v, n), showsRoom > 0.01, room);
    float key = probeCacheKey();
    cacheIrradiance = vec4(pv.rgb, pv.a > 1e-3 ? key : -key);
    cacheRoom = room;
    return;
  }
#endif

  // KHR_materials_clearcoat: a GGX layer with F0 0.04 over the base, on its own normal (its
  // normal map, else the geometric normal). The base below gets what the coat lets through,
  // 1 - coat F(n.v), as the extension defines.
#if PN_CAPTURE
  float coat = 0.0;
#else
  float coat = PN_CLEARCOAT == 0 ? 0.0 : uClearcoat;
#endif
  vec3 coatN = PN_CLEARCOAT == 0 ? n : clearcoatNormal();
  float coatNoV = max(dot(coatN, v), 1e-4);
  float coatRoughness = clamp(uClearcoatRoughness, MIN_PERCEPTUAL_ROUGHNESS, 1.0);
  float coatAlpha = coatRoughness * coatRoughness;
  float baseScale = PN_CLEARCOAT == 0 ? 1.0 : 1.0 - coat * F_Schlick(vec3(0.04), coatNoV).x;

  // KHR_materials_sheen: a Charlie lobe over the base, which receives what the sheen does not
  // reflect (glTF's albedo scaling, 1 - max(sheenColor) E(n.v)). Under the coat, like the base.
#if PN_CAPTURE
  vec3 sheenColor = vec3(0.0);
#else
  vec3 sheenColor = PN_SHEEN == 0 ? vec3(0.0) : uSheenColor;
#endif
  float sheenMax = max(sheenColor.r, max(sheenColor.g, sheenColor.b));
  float sheenA = sheenAlpha(uSheenRoughness);
  float sheenE = sheenMax > 0.0 ? sheenAlbedo(NoV, uSheenRoughness) : 0.0;
  float sheenScale = 1.0 - sheenMax * sheenE;
#if PN_LIGHT_CACHE_WRITE
  // One layer a light (PN_LIGHT_CACHE_WRITE of them; outputs take constant indices).
#define PN_CACHED_SHADING(i)                                                                 \
  vec4(areaShading(areaLightOf(i), n, v, f0, f90, alpha, diffuseColor, baseScale, sheenScale, \
                   sheenColor, sheenA, coat, coatN, coatAlpha) *                            \
           uLightCacheWeight,                                                               \
       uLightCacheWeight)
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
  return;
#endif
#if PN_TRANSMISSION == 2
  // Under the coat and the sheen like the base; the surface's own light was drawn per batch.
  // A smooth surface (at the shading's roughness floor) transmits without scattering: GGX's
  // long tail at that floor would still throw a few samples pixels away.
  float transmitAlpha = s.perceptualRoughness > MIN_PERCEPTUAL_ROUGHNESS ? alpha : 0.0;
  vec3 own = texelFetch(uGlassLight, ivec2(gl_FragCoord.xy), 0).rgb;
  fragColor = vec4(own + baseScale * sheenScale * transmitColor *
                             transmittedRadiance(vWorldPos, n, v, transmitAlpha, uIor),
                   1.0);
  return;
#endif

  vec3 color = vec3(0.0);
  // 1 while the diffuse environment term is the unoccluded E(n): a sky-shadow sample corrects
  // it then; 0 once this frame's diffuse occlusion ray replaced it with what the ray hit.
  float skyLossWeight = 1.0;

  // Environment.
  if (uEnvWeight > 0.0) {
    vec3 irradiance = envIrradiance(n);
    vec3 r = reflect(-v, n);
    vec3 prefiltered = envRadiance(r, s.perceptualRoughness);
    bool diffuseHit = false, specularHit = false;
#if PN_OCCLUSION
    {
      vec2 pixel = gl_FragCoord.xy;
      // Diffuse: one cosine-weighted direction, the ray of a 2x2 block (traced by one of its
      // pixels, a different one each frame), used where the traced pixel lies on this
      // surface. The block is one of those within a pixel of this one, chosen at random once
      // per pixel: its own block alone showed the early frames' noise, and a ray's firefly, as
      // 2x2 squares; another one each frame mixed the blocks' sequences, and the image
      // converged like white noise. Where the traced pixel lies on another surface, the own
      // block's ray is taken if its pixel does not; failing both (a silhouette) the
      // unoccluded estimate stands. E/pi is the unoccluded estimate of the cosine-weighted
      // radiance; a blocked direction contributes the hit's radiance instead.
      ivec2 own = ivec2(gl_FragCoord.xy) / uOcclusionBlock;
      ivec2 offset = (ivec2(floor(hash2(pixel, 8u) * 3.0)) - 1) * (uOcclusionBlock - 1);
      ivec2 pick = (ivec2(gl_FragCoord.xy) + offset) / uOcclusionBlock;
      vec4 ray = texelFetch(uOcclusion, clamp(pick, ivec2(0), textureSize(uOcclusion, 0) - 1), 0);
      vec4 ownRay = texelFetch(uOcclusion, own, 0);
      if (abs(abs(ray.a) - viewDepth) >= rayTolerance) ray = ownRay;
      if (ray.a > 0.0 && abs(ray.a - viewDepth) < rayTolerance) {
        irradiance = ray.rgb * PI;
        skyLossWeight = 0.0;
        diffuseHit = true;
      }
#if PN_BROAD_LOBE
      // A dielectric's broad specular lobe (gpu_scene.h materialFeatures) is occluded like the
      // diffuse one: a second march would cost as much for a few per cent of the light.
      if (diffuseHit) {
        prefiltered = irradiance * INV_PI;
        specularHit = true;
      }
#else
      // Specular: one GGX half vector, reflected, marched here.
      vec3 hit;
      vec3 h = tangentFrame(n) * sampleGgxHalfVector(pixelSample(pixel, 1.0), alpha);
      vec3 sDir = reflect(-v, h);
      if (dot(sDir, n) > 0.0 &&
          traceOcclusion(vWorldPos, sDir, fract(uSequence.y * 5.0 + hash2(pixel, 6u).x), hit)) {
        prefiltered = hit;
        specularHit = true;
      }
#endif
    }
#endif
    // The probe volume answers what the screen-space rays did not: the environment's light and
    // every bounce, with the visibility the probes saw (which also stands in for the sky-shadow
    // correction). Looked up only when needed: a pixel whose rays both hit skips it.
    // Frame 1 (no occlusion) keeps the sky's reflection: it is the frame shown while the view
    // moves, and one frame of a long mean. Elsewhere only surfaces whose specular layer shows
    // enough of the room (reflectance times smoothness) pay for the radiance lookup.
#if PN_OCCLUSION
    float showsRoom = max(specularScale.r, max(specularScale.g, specularScale.b)) *
                      (1.0 - s.perceptualRoughness);
    bool glossy = showsRoom > 0.01 && !specularHit;
#else
    bool glossy = false;
#endif
    vec4 room = vec4(0.0);
    vec4 pv = vec4(0.0);
#if PN_OCCLUSION && PN_PROBE_CACHE
    probeCacheRead(cacheKey, cacheTolerance, pv, room);
#else
    if (PN_PROBES != 0 && (!diffuseHit || glossy)) {
      pv = probeIrradiance(vWorldPos, n, v, r, glossy, room);
    }
#endif
    if (PN_PROBES != 0) {
#if PN_CAPTURE
      // Captures build on what the volume holds, nothing else: each adds a bounce.
      irradiance = pv.rgb;
#else
      if (pv.a > 1e-3) {
        if (!diffuseHit) irradiance = pv.rgb;
        // Glossy reflections of the room: where the probes see geometry toward r, their
        // radiance replaces the sky's, blurred toward the cosine-weighted mean (E / pi) as the
        // surface gets rough (the probes' maps have no mip chain).
        if (glossy) {
          vec3 roomRadiance = mix(room.rgb, pv.rgb * INV_PI, s.perceptualRoughness);
          prefiltered = mix(prefiltered, roomRadiance, room.a);
        }
        skyLossWeight = 0.0;
      }
#endif
    }
    // The broad sheen lobe reflects the cosine-weighted environment (with this frame's
    // occlusion sample), scaled by its albedo: exact in a white furnace.
    color += uEnvWeight * s.occlusion * baseScale *
             (sheenScale * (diffuseColor * irradiance * INV_PI + prefiltered * specularScale) +
              sheenColor * (sheenE * INV_PI) * irradiance);
    if (coat > 0.0) {
      vec3 coatDfg = dfg(coatNoV, coatRoughness);
      vec3 coatPrefiltered = envRadiance(reflect(-v, coatN), coatRoughness);
      color += uEnvWeight * s.occlusion * coat * coatPrefiltered *
               (0.04 * coatDfg.x + coatDfg.y);
    }
  }

#if PN_AREA
  // Area-light samples, sorted by light: a light's unshadowed shading is the same for all of
  // its samples, so it is computed once (or read from the per-view cache) and only the
  // shadow-map visibility differs.
  vec3 shaded = vec3(0.0);
  for (int i = 0; i < PN_AREA_COUNT; ++i) {
#if PN_LIGHT_CACHE
    // The mean over the positions that saw a surface: at a silhouette against the sky the
    // others added nothing, and this sample is on the surface.
    vec4 cached = texelFetch(uLightCache, ivec3(ivec2(gl_FragCoord.xy), uAreaLayer[i]), 0);
    shaded = cached.rgb / max(cached.a, 1e-3);
#else
    if ((PN_AREA_STARTS & (1 << i)) != 0) {
      shaded = areaShading(areaLightOf(i), n, v, f0, f90, alpha, diffuseColor, baseScale,
                           sheenScale, sheenColor, sheenA, coat, coatN, coatAlpha);
    }
#endif
    float visibility = shadowVisibility(int(uAreaShape[i].w), vWorldPos, normalize(vNormal));
    color += uAreaRadiance[i] * visibility * shaded;
  }
#endif
#if PN_PUNCTUAL
  // Punctual lights (KHR_lights_punctual): spot and directional samples with a shadow map each
  // (directional ones from a direction jittered over the light's angular size), point lights
  // unshadowed.
  for (int i = 0; i < PN_PUNCTUAL_COUNT; ++i) {
    vec3 l;
    float attenuation = 1.0;
    int type = int(uPunctualPos[i].w);
    // PN_PUNCTUAL_KINDS (passes/lighting_pass.h punctualKinds) compiles only the kinds of
    // light this batch has: a software rasterizer would run every kind's code for every light.
#if (PN_PUNCTUAL_KINDS & 3) != 0
    if (type == 2) {
#endif
#if (PN_PUNCTUAL_KINDS & 28) != 0
      l = -uPunctualDir[i].xyz;
#endif
#if (PN_PUNCTUAL_KINDS & 16) != 0
      if (uPunctualCone[i].x < 0.0) {
        // Sky-shadow sample: its colour is radiance / pdf of a direction drawn by the sky's
        // luminance, so colour (n.l) is an unbiased estimate of the environment's irradiance
        // and colour (n.l) (V - 1) of what the shadow takes from the diffuse term.
        float NoLs = dot(n, l);
        if (NoLs <= 0.0 || skyLossWeight <= 0.0) continue;
        float vis = shadowVisibility(uPunctualShadow[i], vWorldPos, normalize(vNormal));
        color += uPunctualColor[i] * ((vis - 1.0) * NoLs * INV_PI * skyLossWeight * s.occlusion *
                                      baseScale * sheenScale) *
                 diffuseColor;
        continue;
      }
#endif
#if (PN_PUNCTUAL_KINDS & 15) == 0
      continue;  // sky-shadow samples only
#endif
#if (PN_PUNCTUAL_KINDS & 3) != 0
    }
    if (type != 2) {
      vec3 toLight = uPunctualPos[i].xyz - vWorldPos;
      float d2 = max(dot(toLight, toLight), 1e-8);
      l = toLight * inversesqrt(d2);
      attenuation = 1.0 / d2;
      float range = uPunctualDir[i].w;
      if (range > 0.0) {
        float x = d2 / (range * range);
        attenuation *= saturate(1.0 - x * x);
      }
#if (PN_PUNCTUAL_KINDS & 2) != 0
      if (type == 1) {
        float cd = dot(uPunctualDir[i].xyz, -l);
        float a = saturate(cd * uPunctualCone[i].x + uPunctualCone[i].y);
        attenuation *= a * a;
      }
#endif
    }
#endif
    float NoL = dot(n, l);
    if (NoL <= 0.0 && (coat <= 0.0 || dot(coatN, l) <= 0.0)) continue;
    attenuation *= shadowVisibility(uPunctualShadow[i], vWorldPos, normalize(vNormal));
    vec3 e = uPunctualColor[i] * attenuation;
    vec3 base = diffuseColor * (max(NoL, 0.0) * INV_PI) +
                punctualLobe(n, v, l, f0, f90, alpha, uPunctualDisk[i]);
    if (sheenMax > 0.0) base = sheenScale * base + sheenColor * sheenBrdfCos(n, v, l, sheenA);
    color += e * baseScale * base;
    if (coat > 0.0) {
      color += e * coat * punctualLobe(coatN, v, l, vec3(0.04), 1.0, coatAlpha, uPunctualDisk[i]);
    }
  }

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
