// The texture-unit budget: every sampler the shaders declare has one role in this table and
// its unit is the role's position, so no two features can take a unit by accident, the total
// is checked against WebGL2's guaranteed 16 at compile time and against the device's limit
// when a renderer starts (checkTextureUnits). Roles whose features never meet in one program
// share a unit on purpose: those aliases are listed in passes/limits.h with the reason.
#pragma once

#include <string>

#include "penumbra/error.h"
#include "penumbra/scene.h"

namespace penumbra {

enum class TextureUnit : int {
  // A material's core textures (TextureSlot::BaseColor..Emissive, in that order).
  BaseColor,
  MetallicRoughness,
  Normal,
  Occlusion,
  Emissive,
  EnvCube,       // the prefiltered environment
  Lut,           // the split-sum BRDF table
  Prepass,       // the frame's depth and normals (occlusion rays)
  Accumulated,   // the running mean (screen-space indirect light)
  Shadow,        // the area and spot lights' shadow maps (one depth array)
  PointShadow0,  // point lights' cube shadow maps
  PointShadow1,
  MaterialLayers,  // a material's extension textures, a layer each (gpu/gpu_scene.h)
  ProbeAtlas,      // the probe volume
  ProbeCache,      // its per-view cache
  OcclusionRays,   // this frame's diffuse occlusion rays
  Count
};

inline constexpr int unitOf(TextureUnit u) {
  return static_cast<int>(u);
}
inline constexpr int kTextureUnitsNeeded = unitOf(TextureUnit::Count);
static_assert(kTextureUnitsNeeded <= 16, "WebGL2 guarantees 16 texture units per shader");
static_assert(unitOf(TextureUnit::Emissive) + 1 == kCoreTextureSlots,
              "a material's core textures take the first units, a slot each");

// An error naming both numbers when the context offers fewer fragment texture units than the
// table needs (WebGL2 and OpenGL ES 3.0 guarantee 16, so only a broken driver fails this).
inline Status checkTextureUnits(int available) {
  if (available >= kTextureUnitsNeeded) return {};
  return makeError("this GPU offers " + std::to_string(available) +
                   " texture units per shader; Penumbra needs " +
                   std::to_string(kTextureUnitsNeeded));
}

}  // namespace penumbra
