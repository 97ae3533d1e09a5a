// RenderSettings: everything a render depends on besides the scene and the environment —
// resolution, exposure and tone mapper, environment rotation and intensity, background, and
// the progressive settings (frame count, direct-light delay, occlusion distance, light samples,
// shadow-map size, screen-space indirect light, seed). Scene files and command-line flags
// fill it; docs/scene-format.md lists each field with its default.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "penumbra/error.h"

namespace penumbra {

enum class ToneMapper { PbrNeutral, AcesFitted, Reinhard, None };
const char* toneMapperName(ToneMapper t);
// "pbr-neutral" (or "neutral"), "aces", "reinhard", "none".
Result<ToneMapper> parseToneMapper(std::string_view name);

struct ProgressiveSettings {
  int frames = 128;                // m, the target number of intermediate frames (1..4096)
  float directDelay = 0.3f;        // f_d: direct-light samples start at frame floor(m * f_d)
  float occlusionDistance = 0.5f;  // d_occ in metres (scene units)
  int lightSamples = 0;            // shadow-map samples per area light; 0 = automatic
  int shadowMapSize = 1024;
  bool screenSpaceIndirect = true;  // one-bounce screen-space indirect light
  // Largest radiance one screen-space indirect sample may bring back (0 = no limit): a ray
  // that finds a sun highlight on a mirror ball would otherwise leave a firefly. 10, as the
  // default indirect clamp of Cycles, the reference the evaluation compares against.
  float indirectClamp = 10.0f;
  uint32_t seed = 1;                // rotates every sample sequence
  bool operator==(const ProgressiveSettings&) const = default;
};

struct RenderSettings {
  int width = 1280;
  int height = 720;
  float exposure = 0.0f;  // EV: the image is scaled by 2^exposure before tone mapping
  ToneMapper toneMapper = ToneMapper::PbrNeutral;
  float environmentIntensity = 1.0f;
  float environmentRotation = 0.0f;  // degrees about +Y
  bool showBackground = true;
  float backgroundBlur = 0.0f;  // 0 = sharp, 1 = the roughest prefiltered mip
  ProgressiveSettings progressive;
  bool operator==(const RenderSettings&) const = default;
};

// Checks ranges; the message names the offending setting.
Status validate(const RenderSettings& settings);

}  // namespace penumbra
