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
  // What the lighting shader receives: area lights the shape code in uAreaShape.z
  // (glsl/chunks/area_lights.glsl, PN_LIGHT_<NAME>); punctual lights their plain sample's
  // PunctualSample code (below), which a sample's kind may refine (a sun, a sky shadow).
  int shaderCode;
  // The emitting area (area lights; 0 for the others).
  float (*surfaceArea)(const Light& l);
  // Where the sample with unit-square point u (from progressive::lightSamplePoints) sits.
  glm::vec3 (*samplePoint)(const Light& l, glm::vec2 u);
};

const LightKind& lightKind(LightType type);
std::span<const LightKind> lightKinds();

// The kinds of punctual sample the lighting shader tells apart, one table: a
// KHR_lights_punctual light's own (point, spot, directional), a directional light with an
// angular size (a sun: a disk of directions) and a sky-shadow sample (a direction drawn from
// the environment, shadowed, correcting its diffuse term). A sample's code is its row
// (uPunctualPos.w; PN_SAMPLE_<NAME> in the shaders) and a batch compiles only the kinds it has
// (PN_PUNCTUAL_KINDS, a bit 1 << code each: PN_KIND_<NAME>). The sample's kind alone says what
// its other uniforms mean: no value of theirs doubles as a code.
enum class PunctualSample : int { Point, Spot, Directional, Sun, SkyShadow, Count };

struct PunctualSampleKind {
  PunctualSample sample;
  const char* name;  // for the defines: "sky-shadow" -> PN_SAMPLE_SKY_SHADOW
};

std::span<const PunctualSampleKind> punctualSampleKinds();
inline constexpr uint32_t sampleBit(PunctualSample s) {
  return 1u << static_cast<int>(s);
}
// Every kind's bit: the widest PN_PUNCTUAL_KINDS.
inline constexpr uint32_t kAllPunctualSamples = (1u << static_cast<int>(PunctualSample::Count)) - 1;
// The sample a punctual light's draw is: its plain one, a sun where a directional light has an
// angular size (`sun`), a sky shadow where the draw is one (`skyShadow`).
PunctualSample punctualSample(const Light& light, bool sun, bool skyShadow);
// The kind named `name` in EXT_lights_area (area) or KHR_lights_punctual; null if none.
const LightKind* lightKindNamed(std::string_view name, bool area);

}  // namespace penumbra
