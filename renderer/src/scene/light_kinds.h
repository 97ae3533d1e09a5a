// One descriptor per light type (pbrt-v4's light interface, as a table): its glTF name, how
// its samples spread over it, how its shadow maps project, how the shaders receive it and
// where a sample sits. The glTF parser, the sample distributor's inputs, the shadow passes, the
// lighting pass's uniforms and the shader composer's defines all read it here, so a new kind of
// light is one row (docs/architecture.md, "A new area-light shape").
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include <glm/glm.hpp>

#include "penumbra/scene.h"
#include "progressive/sequences.h"

namespace penumbra {

enum class ShadowProjection {
  Perspective,   // from the sample's point toward the light's direction (area, spot)
  Orthographic,  // fitted to the scene's bounds (directional)
  Cube,          // six faces (point)
};

struct LightKind {
  LightType type;
  const char* name;  // in EXT_lights_area ("rect", "disk") or KHR_lights_punctual
  bool area;         // an emitting surface: luminance, a shadow map per sample over it
  // How the distributor orders its samples (centre outward) and spreads them; Point: one
  // position (a directional light spreads over its angular size: Disk).
  progressive::LightShape samples;
  ShadowProjection shadow;
  // What the lighting shader receives: area lights the shape code in uAreaShape.z, punctual
  // lights the type code in uPunctualPos.w (glsl/chunks/area_lights.glsl, punctual_term.glsl;
  // both from lightDefines()).
  int shaderCode;
  // The emitting area (area lights; 0 for the others).
  float (*surfaceArea)(const Light& l);
  // Where the sample with unit-square point u (from progressive::lightSamplePoints) sits.
  glm::vec3 (*samplePoint)(const Light& l, glm::vec2 u);
};

const LightKind& lightKind(LightType type);
std::span<const LightKind> lightKinds();
// The kind named `name` in EXT_lights_area (area) or KHR_lights_punctual; null if none.
const LightKind* lightKindNamed(std::string_view name, bool area);

}  // namespace penumbra
