// The environment's term of the lighting programs (split sum), with this frame's occlusion
// samples, the probe volume's answer and its per-view cache. Included by
// chunks/lighting_common.glsl after the material, the layers and the occlusion march.
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

#if PN_OCCLUSION || PN_PROBE_CACHE_WRITE
float probeCacheKey() {
  return -(uView * vec4(vWorldPos, 1.0)).z / uProbeDiagonal;
}
#endif

#if PN_OCCLUSION
// Set by setSampleKeys() before any early return (they take derivatives): the probe cache's key and
// how far a jittered sample may move it, and the same for the occlusion rays' linear depth.
float gCacheKey, gCacheTolerance, gViewDepth, gRayTolerance;

// Sets them; called first in main(), before any early return. A jitter moves the sample by
// under a pixel in x and y: the key changes by at most fwidth, plus half-float rounding. The
// same for the occlusion ray taken from a nearby 2x2 block (occlusion_trace.frag), traced up to
// two pixels away in x and y (plus the jitter) on the prepass's half floats.
void setSampleKeys() {
  gCacheKey = probeCacheKey();
  gCacheTolerance = 2.0 * fwidth(gCacheKey) + 2e-3 * gCacheKey;
  gViewDepth = -(uView * vec4(vWorldPos, 1.0)).z;
  gRayTolerance = 2.0 * fwidth(gViewDepth) + 2e-3 * gViewDepth;
}

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
#if PN_ANISOTROPY
  // The stretched lobe's first sample (anisotropicPrefiltered's), so a hit stands for it.
  if (gAnisotropic) {
    h = mat3(gAnisoT, gAnisoB, L.n) *
        sampleGgxAnisotropicHalfVector(pixelSample(pixel, 1.0) * 0.5, gAlphaT, gAlphaB);
  }
#endif
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

#if PN_ANISOTROPY && !PN_CAPTURE
// KHR_materials_anisotropy's reflection of the environment in later frames: the split sum's
// prefiltered term as the lobe's own mean, from four half vectors of the stretched GGX a frame
// (a 2x2 stratification of the pixel's sequence point), each light direction weighted by n.l
// and read at the roughness whose lobe covers the sample's share of solid angle (filtered
// importance sampling; a GGX lobe of alpha a covers about 4 pi a^2). The bent normal's single
// lookup (frame 1, and probe captures) is the extension's sample implementation, which left a
// smooth, strongly stretched metal a third darker than Cycles (AnisotropyStrengthTest).
const int kAnisotropicSamples = 4;
vec3 anisotropicPrefiltered(Layers L) {
  mat3 frame = mat3(gAnisoT, gAnisoB, L.n);
  vec2 u0 = pixelSample(gl_FragCoord.xy, 1.0);
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  for (int i = 0; i < kAnisotropicSamples; ++i) {
    vec2 u = (u0 + vec2(float(i & 1), float(i >> 1))) * 0.5;
    vec3 hl = sampleGgxAnisotropicHalfVector(u, gAlphaT, gAlphaB);
    vec3 h = frame * hl;
    float VoH = dot(L.v, h);
    vec3 l = 2.0 * VoH * h - L.v;
    float NoL = dot(L.n, l);
    float pdf = D_GGXAnisotropic(hl.z, hl.x, hl.y, gAlphaT, gAlphaB) * hl.z /
                (4.0 * max(VoH, 1e-4));
    float a = sqrt(1.0 / (float(kAnisotropicSamples) * max(pdf, 1e-6) * 8.0 * PI));
    float w = VoH > 0.0 ? max(NoL, 0.0) : 0.0;
    sum += w * envRadiance(l, sqrt(min(a, 1.0)));
    weight += w;
  }
  return weight > 0.0 ? sum / weight : envRadiance(specularReflection(L.v, L.n),
                                                   L.perceptualRoughness);
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
#if PN_ANISOTROPY && !PN_CAPTURE
  // From frame 2 (uCoverageFrame >= 0: the camera's later frames).
  if (gAnisotropic && uCoverageFrame >= 0) prefiltered = anisotropicPrefiltered(L);
#endif
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
