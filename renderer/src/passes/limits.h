// Limits shared by the C++ passes and the shaders. The Renderer gives every shader these as
// generated #defines (PN_MAX_SHADOW_MAPS, PN_MAX_PUNCTUAL_LIGHTS, PN_MAX_POINT_SHADOWS, ...), so
// C++ and GLSL cannot disagree; a shader that supports only one value checks it with #error.
// (Texture units are not here: each program hands out its own at link, gl/program.h.)
#pragma once

#include <cctype>
#include <cstdint>
#include <string>

#include "gl/program.h"
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
          {"PN_TEXTURE_SLOTS", std::to_string(kTextureSlotCount)}};
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
// PN_LIGHT_DISK (uAreaShape.z), each punctual sample kind's as PN_SAMPLE_<NAME>
// (uPunctualPos.w) with its bit of PN_PUNCTUAL_KINDS as PN_KIND_<NAME>, and each tone mapper's
// as PN_TONEMAP_<NAME> (penumbra/settings.h), e.g. PN_TONEMAP_ACES: no shader keeps a copy of
// a C++ enum's numbers.
inline gl::Defines commonDefines() {
  gl::Defines d = limitDefines();
  for (const LightKind& k : lightKinds()) {
    d.emplace_back("PN_LIGHT_" + defineName(k.name), std::to_string(k.shaderCode));
  }
  for (const PunctualSampleKind& k : punctualSampleKinds()) {
    d.emplace_back("PN_SAMPLE_" + defineName(k.name), std::to_string(static_cast<int>(k.sample)));
    d.emplace_back("PN_KIND_" + defineName(k.name), std::to_string(sampleBit(k.sample)));
  }
  for (const ToneMapper t : kToneMappers) {
    d.emplace_back("PN_TONEMAP_" + defineName(toneMapperName(t)),
                   std::to_string(static_cast<int>(t)));
  }
  return d;
}

}  // namespace penumbra::passes
