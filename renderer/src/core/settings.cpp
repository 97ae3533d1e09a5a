#include "penumbra/settings.h"

#include "core/settings_json.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

namespace penumbra {

const char* toneMapperName(ToneMapper t) {
  switch (t) {
    case ToneMapper::PbrNeutral:
      return "pbr-neutral";
    case ToneMapper::AcesFitted:
      return "aces";
    case ToneMapper::Reinhard:
      return "reinhard";
    case ToneMapper::None:
      return "none";
  }
  return "?";
}

Result<ToneMapper> parseToneMapper(std::string_view name) {
  std::string n(name);
  std::transform(n.begin(), n.end(), n.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (n == "pbr-neutral" || n == "neutral" || n == "khronos") return ToneMapper::PbrNeutral;
  if (n == "aces" || n == "aces-fitted") return ToneMapper::AcesFitted;
  if (n == "reinhard") return ToneMapper::Reinhard;
  if (n == "none" || n == "linear") return ToneMapper::None;
  return makeError("unknown tone mapper '" + std::string(name) +
                   "' (expected pbr-neutral, aces, reinhard or none)");
}

namespace {

using nlohmann::json;

// One row per setting. get/set convert between the field and a double (bools as 0/1, the tone
// mapper as its index); ranges are checked before set() runs.
#define PN_FIELD(path, T)                                                        \
  [](const RenderSettings& s) -> double { return static_cast<double>(s.path); }, \
      [](RenderSettings& s, double v) { s.path = static_cast<T>(v); }
#define PN_BOOL(path)                                                   \
  [](const RenderSettings& s) -> double { return s.path ? 1.0 : 0.0; }, \
      [](RenderSettings& s, double v) { s.path = v != 0.0; }

const SettingInfo kSchema[] = {
    {"width", "resolution", "0", "", SettingType::Int, 1, 16384, false, false, false, false,
     "image width in pixels (the command line's --size WxH)", PN_FIELD(width, int)},
    {"height", "resolution", "1", "", SettingType::Int, 1, 16384, false, false, false, false,
     "image height in pixels", PN_FIELD(height, int)},
    {"exposure", "", "exposure", "--exposure", SettingType::Float, -32, 32, false, false, false,
     true, "exposure in EV: the image is scaled by 2^exposure before tone mapping",
     PN_FIELD(exposure, float)},
    {"toneMapper", "", "toneMapper", "--tonemap", SettingType::ToneMapper, 0, 3, false, false,
     false, true, "pbr-neutral, aces, reinhard or none",
     [](const RenderSettings& s) -> double { return static_cast<double>(s.toneMapper); },
     [](RenderSettings& s, double v) {
       s.toneMapper = static_cast<ToneMapper>(static_cast<int>(v));
     }},
    {"bloom", "", "bloom", "--bloom", SettingType::Float, 0, 1, false, false, false, true,
     "bloom: the share of the displayed image's light spread by a wide blur (glare around "
     "emissive surfaces and highlights; the mean is kept); 0 off",
     PN_FIELD(bloom, float)},
    {"environmentIntensity", "environment", "intensity", "--env-intensity", SettingType::Float, 0,
     1e6, false, false, false, true, "environment radiance multiplier",
     PN_FIELD(environmentIntensity, float)},
    {"environmentRotation", "environment", "rotation", "--env-rotation", SettingType::Float, -360,
     360, false, false, false, true, "environment rotation about +Y in degrees",
     PN_FIELD(environmentRotation, float)},
    {"sunThreshold", "environment", "sunThreshold", "--sun-threshold", SettingType::Float, -1, 1e9,
     false, false, false, true,
     "a panorama's sun: luminance above which its brightest compact region becomes a "
     "shadow-casting light (-1 automatic, 0 off)",
     PN_FIELD(sunThreshold, float)},
    {"showBackground", "background", "show", "--no-background", SettingType::Bool, 0, 1, false,
     false, false, true, "draw the environment behind the scene (else black)",
     PN_BOOL(showBackground)},
    {"backgroundBlur", "background", "blur", "--background-blur", SettingType::Float, 0, 1, false,
     false, false, true, "background blur: 0 sharp, 1 the roughest prefiltered mip",
     PN_FIELD(backgroundBlur, float)},
    {"transparentBackground", "background", "transparent", "--transparent", SettingType::Bool, 0,
     1, false, false, false, true,
     "leave the pixels the scene does not cover transparent: the image's alpha is the scene's "
     "coverage (PNG), a page shows through the browser's canvas",
     PN_BOOL(transparentBackground)},
    {"shadowIntensity", "ground", "shadowIntensity", "--shadow-intensity", SettingType::Float, 0,
     1, false, false, false, true,
     "a shadow-catching ground under the scene: the share of the light the scene takes from it "
     "(the environment's and the punctual lights') that darkens what is behind it; 0 off",
     PN_FIELD(shadowIntensity, float)},
    {"frames", "progressive", "frames", "--frames", SettingType::Int, 0, 4096, false, false, false,
     true,
     "intermediate frames m, or auto (the default): until the displayed image is measured "
     "converged, at most maxFrames",
     PN_FIELD(progressive.frames, int), true},
    {"maxFrames", "progressive", "maxFrames", "--max-frames", SettingType::Int, 16, 4096, false,
     false, false, true, "the most frames an auto view draws",
     PN_FIELD(progressive.maxFrames, int)},
    {"convergenceThreshold", "progressive", "convergenceThreshold", "--convergence-threshold",
     SettingType::Float, 0.125, 255, false, false, false, true,
     "auto frames: converged when the displayed image's estimated error against the image at "
     "maxFrames (from its change since the checkpoint at about half the frames) is under this "
     "many 8-bit steps (RMS) and that of 99 % of its 8x8 tiles under 3 times it",
     PN_FIELD(progressive.convergenceThreshold, float)},
    {"skipConvergedTiles", "progressive", "skipConvergedTiles", "--no-tile-skip", SettingType::Bool,
     0, 1, false, false, false, true,
     "auto frames: 8x8 tiles measured converged (under half the threshold) stop being shaded, so "
     "later frames go to the regions still changing",
     PN_BOOL(progressive.skipConvergedTiles)},
    {"fd", "progressive", "fd", "--fd", SettingType::Float, 0, 1, false, true, false, true,
     "f_d: direct light starts at frame floor(m f_d)", PN_FIELD(progressive.directDelay, float)},
    // Not the web viewer's: it lowers its own resolution while the camera moves.
    {"previewScale", "progressive", "previewScale", "--preview-scale", SettingType::Float, 0.25, 1,
     false, false, false, false,
     "resolution scale of Renderer::preview, the image a host shows while its view moves "
     "(frame 1, upsampled; the command-line tools never show one)",
     PN_FIELD(progressive.previewScale, float)},
    {"occlusionDistance", "progressive", "occlusionDistance", "--occlusion-distance",
     SettingType::Float, 0, 1e9, false, false, false, true,
     "d_occ, the length of occlusion rays in scene units; 0 = automatic, a quarter of the "
     "scene's bounding-box diagonal",
     PN_FIELD(progressive.occlusionDistance, float)},
    {"lightSamples", "progressive", "lightSamples", "--light-samples", SettingType::Int, 0, 4096,
     false, false, false, true, "shadow-map samples per area light (0 = automatic)",
     PN_FIELD(progressive.lightSamples, int)},
    {"shadowMapSize", "progressive", "shadowMapSize", "--shadow-size", SettingType::Int, 16, 8192,
     false, false, true, true, "shadow-map size in texels (a power of two)",
     PN_FIELD(progressive.shadowMapSize, int)},
    {"screenSpaceIndirect", "progressive", "screenSpaceIndirect", "--no-ssgi", SettingType::Bool, 0,
     1, false, false, false, true, "one-bounce screen-space indirect light",
     PN_BOOL(progressive.screenSpaceIndirect)},
    {"skyShadows", "progressive", "skyShadows", "--sky-shadows", SettingType::Bool, 0, 1, false,
     false, false, true,
     "sky shadows: one environment direction a frame, by luminance, casts a shadow-mapped "
     "shadow on the diffuse environment light",
     PN_BOOL(progressive.skyShadows)},
    {"indirectClamp", "progressive", "indirectClamp", "--indirect-clamp", SettingType::Float, 0,
     1e9, false, false, false, true,
     "largest radiance one screen-space indirect sample brings back (0 = no limit)",
     PN_FIELD(progressive.indirectClamp, float)},
    {"rayFilterFrames", "progressive", "rayFilterFrames", "--ray-filter-frames", SettingType::Int,
     0, 1024, false, false, false, true,
     "early frames' diffuse rays are averaged with their neighbours' on the same surface, the "
     "neighbours' weight fading to none by this frame (less grain than one ray a pixel; 0 off)",
     PN_FIELD(progressive.rayFilterFrames, int)},
    {"directionalAngle", "progressive", "directionalAngle", "--directional-angle",
     SettingType::Float, 0, 30, false, false, false, true,
     "angular diameter of directional lights in degrees (soft shadow edges; 0.53 = the sun)",
     PN_FIELD(progressive.directionalAngle, float)},
    {"probeVolume", "progressive", "probeVolume", "--no-gi", SettingType::Bool, 0, 1, false, false,
     false, true,
     "probe volume: multi-bounce indirect light from irradiance probes over the scene, captured "
     "a few per frame",
     PN_BOOL(progressive.probeVolume)},
    {"probeDensity", "progressive", "probeDensity", "--probe-density", SettingType::Float, 1, 64,
     false, false, false, true,
     "probes along the longest side of the scene's bounds (the other sides get as many per unit "
     "length)",
     PN_FIELD(progressive.probeDensity, float)},
    {"probeRelocation", "progressive", "probeRelocation", "--no-probe-relocation",
     SettingType::Bool, 0, 1, false, false, false, true,
     "probe relocation: a probe buried in geometry or at a wall's nose moves within its cell at "
     "its first capture",
     PN_BOOL(progressive.probeRelocation)},
    {"probesPerFrame", "progressive", "probesPerFrame", "--probes-per-frame", SettingType::Int, 1,
     64, false, false, false, true,
     "probe captures per intermediate frame (a quarter of the volume a frame while it fills, "
     "half as many once every probe has four, at most a sweep per 32 frames then)",
     PN_FIELD(progressive.probesPerFrame, int)},
    {"seed", "progressive", "seed", "--seed", SettingType::UInt, 0, 4294967295.0, false, false,
     false, true, "seed of the sample sequences", PN_FIELD(progressive.seed, uint32_t)},
};
#undef PN_FIELD
#undef PN_BOOL

const char* typeName(SettingType t) {
  switch (t) {
    case SettingType::Bool:
      return "bool";
    case SettingType::Int:
    case SettingType::UInt:
      return "integer";
    case SettingType::Float:
      return "number";
    case SettingType::ToneMapper:
      return "toneMapper";
  }
  return "?";
}

std::string number(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

bool integral(SettingType t) {
  return t == SettingType::Int || t == SettingType::UInt;
}

}  // namespace

Result<double> settingFromJson(const json& v, const SettingInfo& info) {
  const std::string key(info.key);
  switch (info.type) {
    case SettingType::Bool:
      if (!v.is_boolean()) return makeError("setting '" + key + "' must be true or false");
      return v.get<bool>() ? 1.0 : 0.0;
    case SettingType::ToneMapper: {
      if (!v.is_string()) return makeError("setting '" + key + "' must be a tone mapper name");
      auto t = parseToneMapper(v.get<std::string>());
      if (!t) return t.error();
      return static_cast<double>(*t);
    }
    case SettingType::Int:
    case SettingType::UInt:
      if (info.zeroIsAuto && v.is_string() && v.get<std::string>() == "auto") return 0.0;
      // JSON.stringify writes whole numbers without a fraction; 3.5 frames is a mistake.
      if (!v.is_number_integer() &&
          !(v.is_number_float() && std::trunc(v.get<double>()) == v.get<double>())) {
        return makeError("setting '" + key + "' must be an integer" +
                         (info.zeroIsAuto ? " or \"auto\"" : ""));
      }
      if (info.zeroIsAuto && v.get<double>() == 0.0) {
        // "auto" is spelt out: a 0 is more likely a mistake than a wish.
        return makeError("invalid setting: " + key + " 0 (must be " + settingRange(info) + ")");
      }
      return v.is_number_unsigned()  ? static_cast<double>(v.get<uint64_t>())
             : v.is_number_integer() ? static_cast<double>(v.get<int64_t>())
                                     : v.get<double>();
    case SettingType::Float:
      if (!v.is_number()) return makeError("setting '" + key + "' must be a number");
      return v.get<double>();
  }
  return makeError("setting '" + key + "': unknown type");
}

json settingJson(const RenderSettings& s, const SettingInfo& info) {
  const double v = info.get(s);
  switch (info.type) {
    case SettingType::Bool:
      return v != 0.0;
    case SettingType::ToneMapper:
      return toneMapperName(static_cast<ToneMapper>(static_cast<int>(v)));
    case SettingType::Int:
      if (info.zeroIsAuto && v == 0.0) return "auto";
      return static_cast<int64_t>(v);
    case SettingType::UInt:
      return static_cast<uint64_t>(v);
    case SettingType::Float:
      return static_cast<double>(static_cast<float>(v));
  }
  return nullptr;
}

float effectiveOcclusionDistance(const ProgressiveSettings& s, float sceneDiagonal) {
  if (s.occlusionDistance > 0.0f) return s.occlusionDistance;
  return sceneDiagonal > 0.0f && std::isfinite(sceneDiagonal)
             ? kAutoOcclusionFraction * sceneDiagonal
             : 1.0f;
}

std::span<const SettingInfo> settingsSchema() {
  return kSchema;
}

const SettingInfo* findSetting(std::string_view key) {
  for (const SettingInfo& i : kSchema) {
    if (i.key == key) return &i;
  }
  return nullptr;
}

std::string settingRange(const SettingInfo& info) {
  if (info.type == SettingType::Bool) return "true or false";
  if (info.type == SettingType::ToneMapper) return "pbr-neutral, aces, reinhard or none";
  if (integral(info.type)) {
    return (info.zeroIsAuto ? "auto or " + number(info.min + 1) : number(info.min)) + ".." +
           number(info.max);
  }
  return std::string(info.minExclusive ? "(" : "[") + number(info.min) + ", " + number(info.max) +
         (info.maxExclusive ? ")" : "]");
}

Status setSetting(RenderSettings& s, const SettingInfo& info, double v) {
  const bool inRange = std::isfinite(v) && (info.minExclusive ? v > info.min : v >= info.min) &&
                       (info.maxExclusive ? v < info.max : v <= info.max);
  const bool whole = !integral(info.type) || std::trunc(v) == v;
  const bool pow2 =
      !info.powerOfTwo ||
      (whole && inRange && (static_cast<int64_t>(v) & (static_cast<int64_t>(v) - 1)) == 0);
  if (!inRange || !whole || !pow2) {
    return makeError("invalid setting: " + std::string(info.key) + " " + number(v) + " (must be " +
                     (info.powerOfTwo       ? "a power of two in "
                      : integral(info.type) ? "an integer in "
                                            : "in ") +
                     settingRange(info) + ")");
  }
  info.set(s, v);
  return {};
}

Status setSettingText(RenderSettings& s, const SettingInfo& info, std::string_view text) {
  const std::string t(text);
  if (info.type == SettingType::ToneMapper) {
    auto tm = parseToneMapper(t);
    if (!tm) return tm.error();
    return setSetting(s, info, static_cast<double>(*tm));
  }
  if (info.type == SettingType::Bool) {
    if (t == "true" || t == "1" || t == "on") return setSetting(s, info, 1.0);
    if (t == "false" || t == "0" || t == "off") return setSetting(s, info, 0.0);
    return makeError("invalid setting: " + std::string(info.key) + " '" + t +
                     "' (must be true or false)");
  }
  if (info.zeroIsAuto && t == "auto") return setSetting(s, info, 0.0);
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size()) {
    return makeError("invalid setting: " + std::string(info.key) + " '" + t + "' is not " +
                     (integral(info.type) ? "an integer" : "a number"));
  }
  if (info.zeroIsAuto && v == 0.0) {
    return makeError("invalid setting: " + std::string(info.key) + " 0 (must be " +
                     settingRange(info) + ")");
  }
  return setSetting(s, info, v);
}

std::string settingText(const RenderSettings& s, const SettingInfo& info) {
  const json j = settingJson(s, info);
  return j.is_string() ? j.get<std::string>() : j.dump();
}

Status validate(const RenderSettings& s) {
  for (const SettingInfo& info : kSchema) {
    RenderSettings copy = s;
    PN_TRY(setSetting(copy, info, info.get(s)));
  }
  return {};
}

std::string settingsToJson(const RenderSettings& s) {
  json j = json::object();
  for (const SettingInfo& info : kSchema) j[std::string(info.key)] = settingJson(s, info);
  return j.dump();
}

Result<RenderSettings> mergeSettingsJson(const RenderSettings& base, std::string_view text,
                                         bool viewerOnly) {
  const json changes = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (changes.is_discarded() || !changes.is_object()) {
    return makeError("settings must be a JSON object");
  }
  RenderSettings s = base;
  for (const auto& [key, value] : changes.items()) {
    const SettingInfo* info = findSetting(key);
    if (!info || (viewerOnly && !info->viewer)) return makeError("unknown setting '" + key + "'");
    if (value.is_null()) continue;
    auto v = settingFromJson(value, *info);
    if (!v) return v.error();
    PN_TRY(setSetting(s, *info, *v));
  }
  PN_TRY(validate(s));
  return s;
}

std::string settingsSchemaJson() {
  const RenderSettings defaults;
  json all = json::array();
  for (const SettingInfo& info : kSchema) {
    json e = {{"key", info.key},
              {"type", typeName(info.type)},
              {"default", settingJson(defaults, info)},
              {"help", info.help},
              {"viewer", info.viewer},
              {"range", settingRange(info)}};
    if (info.zeroIsAuto) e["auto"] = true;
    if (info.type != SettingType::Bool && info.type != SettingType::ToneMapper) {
      e["min"] = info.min;
      if (std::isfinite(info.max)) e["max"] = info.max;
    }
    all.push_back(std::move(e));
  }
  return all.dump();
}

}  // namespace penumbra
