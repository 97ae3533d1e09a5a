// What the lighting family's programs share (one program per output, each its own file:
// lighting.frag shades a frame's samples; probe_capture.frag, probe_cache.frag, light_cache.frag
// and transmission_compose.frag write the other targets). Generated defines pick the variant
// (one table: passes/lighting_variant.h):
//   PN_OCCLUSION  progressive occlusion and screen-space indirect light
//   PN_AREA       area-light samples with shadow maps
//   PN_PUNCTUAL   KHR_lights_punctual lights
//   PN_CAPTURE, PN_PROBE_CACHE_WRITE, PN_LIGHT_CACHE_WRITE: set in the program of that output
//   PN_LIGHT_CACHE  area-light samples read the lights' per-view cache
//   PN_PROBES     the probe volume is on; PN_PROBE_CACHE: its per-view cache is read
//   PN_TRANSMISSION  1: a transmissive surface's own light (its diffuse base scaled by
//                 1 - transmission); 2: transmission_compose.frag
//   PN_ACCUMULATE  the frame's only batch adds its sample straight to the running mean
// A surface's light: its layers (chunks/material.glsl, chunks/layers.glsl) and the terms:
// environment (chunks/environment_term.glsl), area lights (chunks/area_term.glsl), punctual
// lights (chunks/punctual_term.glsl); emission is each program's own.
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
#if PN_OCCLUSION || PN_TRANSMISSION == 2 || PN_ANISOTROPY
#include "chunks/sampling.glsl"
#endif
#if PN_OCCLUSION
#include "chunks/occlusion.glsl"
#endif

// Limits shared with the C++ side (passes/limits.h), given as generated defines.
const int MAX_AREA = PN_MAX_SHADOW_MAPS;  // area-light samples per pass: one shadow map each
const int MAX_PUNCTUAL = PN_MAX_PUNCTUAL_LIGHTS;

uniform vec4 uViewOrigin;  // (camera position, 1), or (direction to the viewer, 0) if orthographic
uniform float uEnvWeight;  // weight of the environment term in this frame (0 or 1)
// 1 where the surface's emission lights other surfaces (probe captures, screen-space indirect
// light); 0 on an area light's visible face, whose light the analytic area light already gives.
uniform float uIndirectEmission;
// A lamp's face's alpha in the frame: 0 (screen-space indirect light does not reuse it), or 1
// with a transparent background, where alpha is the scene's coverage (a lamp's face is
// opaque then, and reused).
uniform float uLampFaceAlpha;

#if PN_OCCLUSION
// This frame's diffuse occlusion rays, traced at a quarter of the pixels (occlusion_trace.frag):
// rgb the radiance a blocked ray found, alpha the traced pixel's linear depth (positive:
// blocked, negative: not, 0: background).
uniform sampler2D uOcclusion;
uniform int uOcclusionBlock;  // pixels a side of the blocks that trace one ray: 2, or 1
#endif

#include "chunks/layers.glsl"
#if PN_AREA
#include "chunks/area_term.glsl"
#endif
#if PN_PUNCTUAL
#include "chunks/punctual_term.glsl"
#endif
#include "chunks/environment_term.glsl"

vec3 viewDirection() { return normalize(uViewOrigin.xyz - vWorldPos * uViewOrigin.w); }

// The surface's light from every term this variant has (environment, area, punctual), without
// its emission.
vec3 surfaceLight(Layers L, float occlusion) {
  vec3 color = vec3(0.0);
  float skyLossWeight = 1.0;
  if (uEnvWeight > 0.0) color += environmentTerm(L, occlusion, skyLossWeight);
#if PN_AREA
  color += areaTerm(L);
#endif
#if PN_PUNCTUAL
  color += punctualTerm(L, occlusion, skyLossWeight);
#endif
  return color;
}
