// Limits shared by the C++ passes and the shaders. The Renderer gives every shader these as
// generated #defines (PN_MAX_SHADOW_MAPS, PN_MAX_PUNCTUAL_LIGHTS, PN_MAX_POINT_SHADOWS, ...), so
// C++ and GLSL cannot disagree; a shader that supports only one value checks it with #error. Also
// the texture units every program uses.
#pragma once

#include <cctype>
#include <cstdint>
#include <string>

#include "gl/program.h"
#include "gpu/texture_units.h"
#include "penumbra/renderer.h"  // kMaxPunctualLights, public: RenderJob warns past it
#include "penumbra/settings.h"
#include "progressive/probe_relocation.h"
#include "scene/light_kinds.h"

namespace penumbra::passes {

// Shadow maps live at once: the area-light samples one lighting pass shades.
inline constexpr int kMaxShadowMaps = 4;
inline constexpr int kMaxPunctualLights = penumbra::kMaxPunctualLights;
// Area lights the per-view light cache holds (a layer each, written at once: GLES 3.0
// guarantees four draw buffers).
inline constexpr int kMaxCachedLights = 4;
// Point lights with a cube shadow map (the first ones of the scene; the rest stay unshadowed).
inline constexpr int kMaxPointShadows = 2;

// Texture units, from the one table (gpu/texture_units.h). The aliases below share a unit
// with a role that never meets them in one program.
inline constexpr int kUnitEnvCube = unitOf(TextureUnit::EnvCube),
                     kUnitLut = unitOf(TextureUnit::Lut),
                     kUnitPrepass = unitOf(TextureUnit::Prepass),
                     kUnitAccumulated = unitOf(TextureUnit::Accumulated),
                     kUnitShadow = unitOf(TextureUnit::Shadow),
                     kUnitPointShadow = unitOf(TextureUnit::PointShadow0);
inline constexpr int kUnitProbeAtlas = unitOf(TextureUnit::ProbeAtlas),
                     kUnitProbeCache = unitOf(TextureUnit::ProbeCache),
                     kUnitOcclusion = unitOf(TextureUnit::OcclusionRays);
static_assert(kUnitPointShadow + kMaxPointShadows - 1 == unitOf(TextureUnit::PointShadow1),
              "a unit per shadowed point light");
// Transmissive surfaces' compose pass: the frame's copy, and their own light (in the cache's
// and the rays' units: the compose pass reads neither).
inline constexpr int kUnitBehind = kUnitOcclusion, kUnitGlassLight = kUnitProbeCache;
// The area lights' per-view cache: in the second point shadow's unit (a batch with point-light
// cube maps evaluates its lights instead).
inline constexpr int kUnitLightCache = unitOf(TextureUnit::PointShadow1);

// The kinds of punctual sample a lighting batch can hold, as bits of PN_PUNCTUAL_KINDS: only
// the kinds a batch has are compiled (passes/lighting_pass.h punctualKinds). The shaders get
// them as PN_KIND_POINT, ... (limitDefines).
enum PunctualKindBits : uint32_t {
  kKindPoint = 1,
  kKindSpot = 2,
  kKindSun = 4,          // directional with an angular size (a disk of directions)
  kKindDirectional = 8,  // directional without
  kKindSkyShadow = 16,   // a sky-shadow sample (chunks/punctual_term.glsl)
  kKindsAll = 31,
};

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
          {"PN_PROBE_CAPTURE_SIZE", std::to_string(kProbeCaptureSize)},
          {"PN_PROBE_BURIED_SHARE", std::to_string(progressive::kProbeBuriedShare)},
          {"PN_TEXTURE_SLOTS", std::to_string(kTextureSlotCount)},
          {"PN_KIND_POINT", std::to_string(kKindPoint)},
          {"PN_KIND_SPOT", std::to_string(kKindSpot)},
          {"PN_KIND_SUN", std::to_string(kKindSun)},
          {"PN_KIND_DIRECTIONAL", std::to_string(kKindDirectional)},
          {"PN_KIND_SKY_SHADOW", std::to_string(kKindSkyShadow)}};
}

// "pbr-neutral" -> "PBR_NEUTRAL": a name as part of a #define.
inline std::string defineName(const char* name) {
  std::string out;
  for (const char* c = name; *c; ++c) {
    out += *c == '-' ? '_' : static_cast<char>(std::toupper(static_cast<unsigned char>(*c)));
  }
  return out;
}

// Every shader also gets each light kind's code (scene/light_kinds.h) as PN_LIGHT_<NAME>, e.g.
// PN_LIGHT_DISK (uAreaShape.z) and PN_LIGHT_SPOT (uPunctualPos.w), and each tone mapper's as
// PN_TONEMAP_<NAME> (penumbra/settings.h), e.g. PN_TONEMAP_ACES: no shader keeps a copy of a
// C++ enum's numbers.
inline gl::Defines commonDefines() {
  gl::Defines d = limitDefines();
  for (const LightKind& k : lightKinds()) {
    d.emplace_back("PN_LIGHT_" + defineName(k.name), std::to_string(k.shaderCode));
  }
  for (const ToneMapper t : kToneMappers) {
    d.emplace_back("PN_TONEMAP_" + defineName(toneMapperName(t)),
                   std::to_string(static_cast<int>(t)));
  }
  return d;
}

}  // namespace penumbra::passes
