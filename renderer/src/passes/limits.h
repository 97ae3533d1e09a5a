// Limits shared by the C++ passes and the shaders. The Renderer gives every shader these as
// generated #defines (PN_MAX_SHADOW_MAPS, PN_MAX_PUNCTUAL_LIGHTS, PN_MAX_POINT_SHADOWS), so C++ and
// GLSL cannot disagree; a shader that supports only one value checks it with #error. Also the
// texture units every program uses.
#pragma once

#include <string>

#include "gl/program.h"
#include "gpu/gpu_scene.h"      // kClearcoatNormalUnit
#include "penumbra/renderer.h"  // kMaxPunctualLights, public: RenderJob warns past it

namespace penumbra::passes {

// Shadow maps live at once: the area-light samples one lighting pass shades.
inline constexpr int kMaxShadowMaps = 4;
inline constexpr int kMaxPunctualLights = penumbra::kMaxPunctualLights;
// Area lights the per-view light cache holds (a layer each, written at once: GLES 3.0
// guarantees four draw buffers).
inline constexpr int kMaxCachedLights = 4;
// Point lights with a cube shadow map (the first ones of the scene; the rest stay unshadowed).
inline constexpr int kMaxPointShadows = 2;

// Texture units: 0..4 material, then these, within WebGL2's guaranteed 16. The shadow maps
// share one unit (a depth texture array).
inline constexpr int kUnitEnvCube = 5, kUnitLut = 6, kUnitPrepass = 7, kUnitAccumulated = 8,
                     kUnitShadow = 9, kUnitPointShadow = kUnitShadow + 1;
// The probe volume's atlas (irradiance, depth moments and radiance in one texture), the
// per-view cache of its lookups (passes/lighting_pass.h; a two-layer array), and this frame's
// diffuse occlusion rays, traced at a quarter of the pixels (passes/occlusion_pass.h).
inline constexpr int kUnitProbeAtlas = 13, kUnitProbeCache = 14, kUnitOcclusion = 15;
// Transmissive surfaces' compose pass: the frame's copy, and their own light (in the cache's
// and the rays' units: the compose pass reads neither). Unit 12 is the clearcoat's normal map
// (gpu/gpu_scene.h).
inline constexpr int kUnitBehind = kUnitOcclusion, kUnitGlassLight = kUnitProbeCache;
// The area lights' per-view cache: in the second point shadow's unit (a batch with point-light
// cube maps evaluates its lights instead).
inline constexpr int kUnitLightCache = kUnitPointShadow + 1;
static_assert(kClearcoatNormalUnit == kUnitPointShadow + kMaxPointShadows &&
                  kClearcoatNormalUnit < kUnitProbeAtlas,
              "the clearcoat normal map's unit is taken");
static_assert(kUnitPointShadow + kMaxPointShadows <= kUnitProbeAtlas,
              "the point shadows overlap the probe volume's units");
static_assert(kUnitOcclusion < 16, "WebGL2 guarantees 16 texture units");

// Probe volume: interior texels of a probe's octahedral irradiance, depth-moment and radiance
// maps (each tile has a one-texel border), and the face size of a probe's cube capture.
inline constexpr int kProbeIrradianceTexels = 6, kProbeDepthTexels = 10, kProbeRadianceTexels = 14,
                     kProbeCaptureSize = 16;

inline gl::Defines limitDefines() {
  return {{"PN_MAX_SHADOW_MAPS", std::to_string(kMaxShadowMaps)},
          {"PN_MAX_PUNCTUAL_LIGHTS", std::to_string(kMaxPunctualLights)},
          {"PN_MAX_POINT_SHADOWS", std::to_string(kMaxPointShadows)},
          {"PN_PROBE_IRRADIANCE_TEXELS", std::to_string(kProbeIrradianceTexels)},
          {"PN_PROBE_DEPTH_TEXELS", std::to_string(kProbeDepthTexels)},
          {"PN_PROBE_RADIANCE_TEXELS", std::to_string(kProbeRadianceTexels)},
          {"PN_PROBE_CAPTURE_SIZE", std::to_string(kProbeCaptureSize)}};
}

}  // namespace penumbra::passes
