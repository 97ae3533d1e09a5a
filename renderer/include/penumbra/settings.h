// RenderSettings: everything a render depends on besides the scene and the environment —
// resolution, exposure and tone mapper, environment rotation and intensity, background, and
// the progressive settings (frame count, direct-light delay, occlusion distance, light samples,
// shadow-map size, screen-space indirect light, seed). Scene files and command-line flags
// fill it; docs/scene-format.md lists each field with its default.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "penumbra/error.h"

namespace penumbra {

enum class ToneMapper { PbrNeutral, AcesFitted, Reinhard, None };
// Every value, in order: the shaders get each as PN_TONEMAP_<NAME> (passes/limits.h).
inline constexpr ToneMapper kToneMappers[] = {ToneMapper::PbrNeutral, ToneMapper::AcesFitted,
                                              ToneMapper::Reinhard, ToneMapper::None};
const char* toneMapperName(ToneMapper t);
// "pbr-neutral" (or "neutral"), "aces", "reinhard", "none".
Result<ToneMapper> parseToneMapper(std::string_view name);

struct ProgressiveSettings {
  // m, the number of intermediate frames (1..4096), or 0 ("auto"): frames until the displayed
  // image is measured converged (progressive/convergence.h), at most maxFrames.
  int frames = 0;
  int maxFrames = 1024;  // auto's cap
  // Auto: converged when the displayed image's error against the image at maxFrames (8-bit
  // steps, RMS), estimated from its change since the checkpoint at about half the frames, is
  // under this and that of 99 % of its 8x8 tiles under three times this
  // (progressive/convergence.h).
  float convergenceThreshold = 1.0f;
  // Auto: adaptive frames. Tiles measured converged stop being shaded and accumulated (a
  // stencil mask), so the remaining frames go to penumbrae, glossy reflections and edges
  // (progressive/convergence.h, TileSkip).
  bool skipConvergedTiles = true;
  float directDelay = 0.3f;  // f_d: direct-light samples start at frame floor(m * f_d)
  // Renderer::preview, the image shown while the view moves: frame 1 (environment only) drawn
  // at this fraction of the width and height and upsampled, a quarter of the pixels at 0.5.
  // Not part of the mean.
  float previewScale = 0.5f;
  // d_occ in scene units; 0 = automatic: kAutoOcclusionFraction of the scene's bounding-box
  // diagonal, so a model in millimetres and a room in metres both work without a setting.
  float occlusionDistance = 0.0f;
  int lightSamples = 0;  // shadow-map samples per area light; 0 = automatic
  int shadowMapSize = 1024;
  // One-bounce screen-space indirect light. Off: a blocked diffuse ray keeps the probe volume's
  // light where the volume answers (it saw the blocker), else removes its direction's sky.
  bool screenSpaceIndirect = true;
  // Sky shadows: from frame 2, one direction per frame drawn from the environment's (sunless)
  // luminance gets a directional shadow map, and the light its shadow takes is subtracted from
  // the diffuse environment term, so objects shade what is under them at any distance. Off by
  // default: without multi-bounce indirect light the light the shadowing surfaces would
  // reflect back is missing, and the evaluation's product scene moved away from Cycles.
  bool skyShadows = false;
  // Largest radiance one screen-space indirect sample may bring back (0 = no limit): a ray
  // that finds a sun highlight on a mirror ball would otherwise leave a firefly. 10, as the
  // default indirect clamp of Cycles, the reference the evaluation compares against.
  float indirectClamp = 10.0f;
  // Early frames show their diffuse rays through an edge-aware filter over the neighbouring
  // blocks' rays (same depth and normal), its weight fading to none by this frame: a single
  // ray per pixel made frames 2-8 grainier than frame 1 (issue #59). 0: off.
  int rayFilterFrames = 16;
  // Angular diameter of directional lights in degrees: their shadow-map samples spread over
  // it, so shadow edges soften with distance as under the sun (0.53 degrees).
  float directionalAngle = 0.53f;
  // Probe volume: world-space indirect light from a grid of irradiance probes over the scene's
  // bounds, captured a few a frame (docs/architecture.md). Diffuse light that screen-space
  // tracing cannot resolve comes from it instead of the distant environment.
  bool probeVolume = true;
  float probeDensity = 4.0f;    // probes along the scene's longest side (the others follow)
  bool probeRelocation = true;  // probes move out of geometry and off walls within their cells
  int probesPerFrame = 2;       // probe captures per intermediate frame
  uint32_t seed = 1;            // rotates every sample sequence
  bool operator==(const ProgressiveSettings&) const = default;
};

// The frames the sample plan covers: m, or auto's cap.
inline int planFrames(const ProgressiveSettings& s) {
  return s.frames > 0 ? s.frames : s.maxFrames;
}

// The automatic occlusion distance as a fraction of the scene's bounding-box diagonal.
inline constexpr float kAutoOcclusionFraction = 0.25f;
// The occlusion distance in effect for a scene whose bounding-box diagonal is `sceneDiagonal`
// (0 or less: no geometry, then 1 unit).
float effectiveOcclusionDistance(const ProgressiveSettings& settings, float sceneDiagonal);

struct RenderSettings {
  int width = 1280;
  int height = 720;
  float exposure = 0.0f;  // EV: the image is scaled by 2^exposure before tone mapping
  ToneMapper toneMapper = ToneMapper::PbrNeutral;
  // Bloom: the share of the displayed image's light spread by a wide, energy-conserving blur
  // (glare around emissive surfaces and highlights); 0 off (passes/effects/bloom.cpp).
  float bloom = 0.0f;
  float environmentIntensity = 1.0f;
  float environmentRotation = 0.0f;  // degrees about +Y
  // When a panorama is prefiltered on load: luminance above which its brightest compact region
  // becomes a shadow-casting sun (ibl::extractSun). -1 automatic, 0 off. Packed files carry
  // the sun penumbra-prefilter found.
  float sunThreshold = -1.0f;
  bool showBackground = true;
  float backgroundBlur = 0.0f;  // 0 = sharp, 1 = the roughest prefiltered mip
  // The pixels the scene leaves are transparent instead (no background drawn): the displayed
  // image's alpha is the scene's coverage, converging at its edges like every other term (a
  // PNG with alpha; a page shows through the browser's canvas).
  bool transparentBackground = false;
  // A shadow-catching ground under the scene (model-viewer's shadow-intensity): the plane under
  // the scene's bounds darkens what is behind it (the background, or the page with a
  // transparent background) by this share of the light the scene takes from it: the
  // environment's (sky-shadow samples: on with it) and the punctual lights'. 0 off.
  float shadowIntensity = 0.0f;
  ProgressiveSettings progressive;
  bool operator==(const RenderSettings&) const = default;
};

// Checks ranges; the message names the offending setting.
Status validate(const RenderSettings& settings);

// ---------------------------------------------------------------- the settings schema
// Every setting once: its key, type, range, default, help, where it lives in a scene file and
// its command-line flag. Validation, scene-file reading and writing, the CLI flags, the wasm
// settings bridge and the JS API's accepted keys are all derived from this table.

enum class SettingType { Bool, Int, UInt, Float, ToneMapper };

struct SettingInfo {
  std::string_view key;      // the JS API key, also the key in the scene file's group
  std::string_view group;    // scene-file object holding it ("" = top level, "resolution":
                             // the [width, height] pair)
  std::string_view fileKey;  // its name in that object
  std::string_view flag;     // command-line flag ("" = none); a Bool whose flag starts with
                             // "--no-" is a switch that sets it to false
  SettingType type;
  double min, max;
  bool minExclusive, maxExclusive;
  bool powerOfTwo;
  bool viewer;  // settable through the web viewer's setSettings (the canvas sets the size)
  std::string_view help;
  // Number, 0/1 or the ToneMapper's index; set() takes a value already checked.
  double (*get)(const RenderSettings&);
  void (*set)(RenderSettings&, double);
  bool zeroIsAuto = false;  // an Int whose 0 reads and writes as "auto"
};

// The whole table, in documentation order.
std::span<const SettingInfo> settingsSchema();
// nullptr when no setting has that key.
const SettingInfo* findSetting(std::string_view key);
// Checks one value against its entry ("invalid setting: <key> ..." on failure) and stores it.
Status setSetting(RenderSettings& settings, const SettingInfo& info, double value);
// Parses text as the setting's type (true/false/1/0 for Bool, a name for ToneMapper), checks
// it and stores it. Used for command-line values.
Status setSettingText(RenderSettings& settings, const SettingInfo& info, std::string_view text);
// The setting as text, as setSettingText reads it back.
std::string settingText(const RenderSettings& settings, const SettingInfo& info);
// The range as text, e.g. "1..4096" or "(0, inf)", for help and messages.
std::string settingRange(const SettingInfo& info);

// All settings as one flat JSON object {key: value} (the web API's form).
std::string settingsToJson(const RenderSettings& settings);
// Applies the keys of a flat JSON object on top of `base`. Unknown keys, wrong types and
// values out of range are errors naming the key; `viewerOnly` also refuses keys the viewer
// does not take. The result is validated.
Result<RenderSettings> mergeSettingsJson(const RenderSettings& base, std::string_view json,
                                         bool viewerOnly = false);
// The schema as JSON: [{key, type, min, max, default, help, viewer}, ...] for the JS API.
std::string settingsSchemaJson();

}  // namespace penumbra
