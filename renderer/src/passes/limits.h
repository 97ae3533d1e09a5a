// Limits shared by the C++ passes and the shaders. The Renderer gives every shader these as
// generated #defines (PN_MAX_SHADOW_MAPS, PN_MAX_PUNCTUAL_LIGHTS), so C++ and GLSL cannot
// disagree; a shader that supports only one value checks it with #error. Also the texture
// units every program uses.
#pragma once

#include <string>

#include "gl/program.h"
#include "penumbra/renderer.h"  // kMaxPunctualLights, public: RenderJob warns past it

namespace penumbra::passes {

// Shadow maps live at once: the area-light samples one lighting pass shades.
inline constexpr int kMaxShadowMaps = 4;
inline constexpr int kMaxPunctualLights = penumbra::kMaxPunctualLights;

// Texture units: 0..4 material, then these (shadow maps from kUnitShadow on).
inline constexpr int kUnitEnvCube = 5, kUnitLut = 6, kUnitPrepass = 7, kUnitAccumulated = 8,
                     kUnitShadow = 9;

inline gl::Defines limitDefines() {
  return {{"PN_MAX_SHADOW_MAPS", std::to_string(kMaxShadowMaps)},
          {"PN_MAX_PUNCTUAL_LIGHTS", std::to_string(kMaxPunctualLights)}};
}

}  // namespace penumbra::passes
