#include "penumbra/scene_file.h"

#include "core/settings_json.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <type_traits>

#include <nlohmann/json.hpp>

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string resolve(const std::string& base, const std::string& p) {
  if (p.empty() || fs::path(p).is_absolute() || base.empty()) return p;
  return (fs::path(base) / p).lexically_normal().string();
}

void warnUnknown(const json& obj, const std::set<std::string>& known, const std::string& where,
                 std::vector<std::string>& warnings) {
  for (const auto& [k, v] : obj.items()) {
    if (!known.count(k)) warnings.push_back("unknown key '" + k + "' in " + where + " (ignored)");
  }
}

// True when every number in v (a number or an array of them) converts to the integer type I
// without overflow. nlohmann's get<int>() static_casts a floating-point value, and one beyond
// the target's range (e.g. 6e127) is undefined behaviour (found by tests/fuzz/fuzz_scene_json).
template <class I>
bool fitsIntegral(const json& v) {
  if (v.is_array()) {
    for (const auto& e : v)
      if (!fitsIntegral<I>(e)) return false;
    return true;
  }
  constexpr double lo = static_cast<double>(std::numeric_limits<I>::min()) - 1.0;
  constexpr double hi = static_cast<double>(std::numeric_limits<I>::max()) + 1.0;
  if (v.is_number_float()) {
    const double d = v.get<double>();
    return d > lo && d < hi;  // false for NaN
  }
  if (v.is_number_unsigned()) {
    return v.get<uint64_t>() <= static_cast<uint64_t>(std::numeric_limits<I>::max());
  }
  if (v.is_number_integer()) {
    const int64_t i = v.get<int64_t>();
    return static_cast<double>(i) > lo && static_cast<double>(i) < hi;
  }
  return true;  // not a number: get<T>() reports the wrong type
}

template <class T>
struct IntegralOf {
  using type = T;
};
template <class T>
struct IntegralOf<std::vector<T>> {
  using type = T;
};

// Reads obj[key] into out when present; the type must match.
template <class T>
Status read(const json& obj, const char* key, T& out, const std::string& where) {
  auto it = obj.find(key);
  if (it == obj.end()) return {};
  using I = typename IntegralOf<T>::type;
  if constexpr (std::is_integral_v<I> && !std::is_same_v<I, bool>) {
    if (!fitsIntegral<I>(*it)) return makeError(where + ": '" + key + "' is out of range");
  }
  try {
    out = it->template get<T>();
  } catch (const json::exception&) {
    return makeError(where + ": '" + key + "' has the wrong type");
  }
  return {};
}

// The scene-file groups of the settings schema, and the keys each may hold.
std::set<std::string> groupKeys(std::string_view group) {
  std::set<std::string> keys;
  for (const SettingInfo& info : settingsSchema()) {
    if (info.group == group) keys.insert(std::string(info.fileKey));
  }
  return keys;
}

// One setting from its JSON value, checked by the schema.
Status readSetting(const json& v, const SettingInfo& info, RenderSettings& s,
                   const std::string& where) {
  auto value = settingFromJson(v, info);
  if (!value) return makeError(where + ": " + value.message());
  if (auto st = setSetting(s, info, *value); !st) return makeError(where + ": " + st.message());
  return {};
}

// Reads every setting of `group` present in `obj`.
Status readGroup(const json& obj, std::string_view group, RenderSettings& s,
                 const std::string& where) {
  for (const SettingInfo& info : settingsSchema()) {
    if (info.group != group) continue;
    auto it = obj.find(std::string(info.fileKey));
    if (it == obj.end()) continue;
    PN_TRY(readSetting(*it, info, s, where));
  }
  return {};
}

}  // namespace

Result<EnvironmentSpec> parseEnvironmentSpec(std::string_view text, const std::string& baseDir) {
  EnvironmentSpec spec;
  const std::string t(text);
  if (t.empty()) return makeError("environment: empty (expected none, studio, r,g,b or a file)");
  if (t == "none" || t == "black") {
    spec.kind = EnvironmentSpec::Kind::None;
  } else if (t == "studio") {
    spec.kind = EnvironmentSpec::Kind::Studio;
  } else if (t == "default") {
    spec.kind = EnvironmentSpec::Kind::Default;
  } else if (t.find(',') != std::string::npos && !fs::exists(resolve(baseDir, t))) {
    float r = 0, g = 0, b = 0;
    char tail = 0;
    if (std::sscanf(t.c_str(), "%f,%f,%f%c", &r, &g, &b, &tail) != 3 || !std::isfinite(r) ||
        !std::isfinite(g) || !std::isfinite(b) || r < 0 || g < 0 || b < 0) {
      return makeError("environment '" + t +
                       "': expected none, studio, r,g,b (three radiances >= 0) or a file");
    }
    spec.kind = EnvironmentSpec::Kind::Uniform;
    spec.radiance = glm::vec3(r, g, b);
  } else {
    spec.kind = EnvironmentSpec::Kind::File;
    spec.path = resolve(baseDir, t);
  }
  return spec;
}

std::string environmentSpecText(const EnvironmentSpec& spec) {
  switch (spec.kind) {
    case EnvironmentSpec::Kind::Default:
      return "default";
    case EnvironmentSpec::Kind::None:
      return "none";
    case EnvironmentSpec::Kind::Studio:
      return "studio";
    case EnvironmentSpec::Kind::File:
      return spec.path;
    case EnvironmentSpec::Kind::Uniform: {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.9g,%.9g,%.9g", spec.radiance.r, spec.radiance.g,
                    spec.radiance.b);
      return buf;
    }
  }
  return "default";
}

namespace {

// The scene file's "environment": a name (file, none, studio) or an object (file, uniform or
// preset, and the environment settings).
Status readEnvironment(const json& it, const std::string& baseDir, const std::string& name,
                       SceneFile& sf) {
  RenderSettings& s = sf.settings;
  auto fail = [&](const Error& e) { return makeError(name + ": " + e.message); };
  if (it.is_string()) {
    auto spec = parseEnvironmentSpec(it.get<std::string>(), baseDir);
    if (!spec) return fail(spec.error());
    sf.environment = *spec;
  } else if (it.is_object()) {
    std::set<std::string> known = groupKeys("environment");
    known.insert({"file", "uniform", "preset"});
    warnUnknown(it, known, "environment", sf.warnings);
    std::string file, preset;
    if (auto st = read(it, "file", file, "environment"); !st) return fail(st.error());
    if (auto st = read(it, "preset", preset, "environment"); !st) return fail(st.error());
    std::vector<float> uni;
    if (auto st = read(it, "uniform", uni, "environment"); !st) return fail(st.error());
    if (int(!file.empty()) + int(!preset.empty()) + int(it.contains("uniform")) > 1) {
      return makeError(name + ": environment: give one of 'file', 'uniform' and 'preset'");
    }
    if (!file.empty()) {
      sf.environment.kind = EnvironmentSpec::Kind::File;
      sf.environment.path = resolve(baseDir, file);
    } else if (!preset.empty()) {
      if (preset != "none" && preset != "studio") {
        return makeError(name + ": environment.preset must be \"none\" or \"studio\"");
      }
      auto spec = parseEnvironmentSpec(preset);
      if (!spec) return fail(spec.error());
      sf.environment = *spec;
    } else if (it.contains("uniform")) {
      if (uni.size() != 3 || !std::isfinite(uni[0]) || !std::isfinite(uni[1]) ||
          !std::isfinite(uni[2]) || uni[0] < 0 || uni[1] < 0 || uni[2] < 0) {
        return makeError(name + ": environment.uniform must be [r, g, b] (radiances >= 0)");
      }
      sf.environment.kind = EnvironmentSpec::Kind::Uniform;
      sf.environment.radiance = glm::vec3(uni[0], uni[1], uni[2]);
    }
    if (auto st = readGroup(it, "environment", s, "environment"); !st) return fail(st.error());
  } else {
    return makeError(name + ": 'environment' must be a file name, none, studio or an object");
  }
  return {};
}

// The scene file's "probeVolume": an explicit box and/or probe counts.
Status readProbeVolume(const json& it, const std::string& name, SceneFile& sf) {
  if (!it.is_object()) return makeError(name + ": 'probeVolume' must be an object");
  warnUnknown(it, {"min", "max", "counts"}, "probeVolume", sf.warnings);
  auto vec3 = [&](const char* key, glm::vec3& out) -> bool {
    auto v = it.find(key);
    if (v == it.end()) return false;
    if (!v->is_array() || v->size() != 3) return false;
    for (int a = 0; a < 3; ++a) {
      if (!(*v)[a].is_number() || !std::isfinite((*v)[a].get<double>())) return false;
      out[a] = (*v)[a].get<float>();
    }
    return true;
  };
  ProbeVolumeSpec& pv = sf.probeVolume;
  const bool hasMin = it.contains("min"), hasMax = it.contains("max");
  if (hasMin || hasMax) {
    if (!vec3("min", pv.min) || !vec3("max", pv.max) || !(pv.min.x < pv.max.x) ||
        !(pv.min.y < pv.max.y) || !(pv.min.z < pv.max.z)) {
      return makeError(name +
                       ": 'probeVolume' needs both 'min' and 'max' as [x, y, z], with "
                       "min below max on every axis");
    }
    pv.hasBox = true;
  }
  if (auto c = it.find("counts"); c != it.end()) {
    bool ok = c->is_array() && c->size() == 3;
    for (int a = 0; ok && a < 3; ++a) {
      ok = (*c)[a].is_number_integer() && (*c)[a].get<int64_t>() >= 1 &&
           (*c)[a].get<int64_t>() <= 64;
      if (ok) pv.counts[a] = (*c)[a].get<int>();
    }
    if (!ok) return makeError(name + ": 'probeVolume' 'counts' must be three integers in 1..64");
  }
  return {};
}

}  // namespace

Result<SceneFile> parseSceneJson(const std::string& text, const std::string& baseDir,
                                 const std::string& name) {
  json doc = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (doc.is_discarded()) return makeError(name + ": not valid JSON");
  if (!doc.is_object()) return makeError(name + ": a scene file is a JSON object");
  SceneFile sf;
  RenderSettings& s = sf.settings;
  std::set<std::string> topLevel = groupKeys("");
  topLevel.insert({"gltf", "environment", "camera", "variant", "animation", "time", "resolution",
                   "background", "progressive", "probeVolume", "$schema", "comment"});
  warnUnknown(doc, topLevel, "the scene file", sf.warnings);
  auto fail = [&](const Error& e) { return makeError(name + ": " + e.message); };

  std::string gltf;
  if (auto st = read(doc, "gltf", gltf, "scene"); !st) return fail(st.error());
  if (gltf.empty()) return makeError(name + ": 'gltf' (the model to render) is missing");
  sf.gltfPath = resolve(baseDir, gltf);

  if (auto it = doc.find("environment"); it != doc.end()) {
    PN_TRY(readEnvironment(*it, baseDir, name, sf));
  }
  for (const char* key : {"camera", "variant", "animation"}) {
    std::string& out = std::string(key) == "camera"    ? sf.camera
                       : std::string(key) == "variant" ? sf.variant
                                                       : sf.animation;
    auto it = doc.find(key);
    if (it == doc.end()) continue;
    if (it->is_string()) {
      out = it->get<std::string>();
    } else if (it->is_number_integer()) {
      if (!fitsIntegral<int>(*it)) {
        return makeError(name + ": '" + key + "' index is out of range");
      }
      out = std::to_string(it->get<int>());
    } else {
      return makeError(name + ": '" + key + "' must be a name or an index");
    }
  }
  if (auto it = doc.find("time"); it != doc.end()) {
    if (!it->is_number() || !std::isfinite(it->get<double>()) ||
        std::fabs(it->get<double>()) > 1e7) {
      return makeError(name + ": 'time' must be a number of seconds");
    }
    sf.time = it->get<float>();
  }
  if (auto it = doc.find("resolution"); it != doc.end()) {
    if (!it->is_array() || it->size() != 2) {
      return makeError(name + ": 'resolution' must be [width, height]");
    }
    for (const SettingInfo& info : settingsSchema()) {
      if (info.group != "resolution") continue;
      const json& v = (*it)[info.fileKey == "0" ? 0 : 1];
      if (auto st = readSetting(v, info, s, "resolution"); !st) return fail(st.error());
    }
  }
  if (auto it = doc.find("probeVolume"); it != doc.end()) {
    PN_TRY(readProbeVolume(*it, name, sf));
  }
  if (auto st = readGroup(doc, "", s, "scene"); !st) return fail(st.error());
  for (const char* group : {"background", "progressive"}) {
    auto it = doc.find(group);
    if (it == doc.end()) continue;
    if (!it->is_object()) return makeError(name + ": '" + group + "' must be an object");
    warnUnknown(*it, groupKeys(group), group, sf.warnings);
    if (auto st = readGroup(*it, group, s, group); !st) return fail(st.error());
  }
  if (auto st = validate(s); !st) return fail(st.error());
  return sf;
}

std::string sceneFileJson(const SceneFile& sf) {
  json doc = json::object();
  doc["gltf"] = sf.gltfPath;
  json env = json::object();
  switch (sf.environment.kind) {
    case EnvironmentSpec::Kind::Default:
      break;
    case EnvironmentSpec::Kind::None:
      env["preset"] = "none";
      break;
    case EnvironmentSpec::Kind::Studio:
      env["preset"] = "studio";
      break;
    case EnvironmentSpec::Kind::File:
      env["file"] = sf.environment.path;
      break;
    case EnvironmentSpec::Kind::Uniform:
      env["uniform"] = {sf.environment.radiance.r, sf.environment.radiance.g,
                        sf.environment.radiance.b};
      break;
  }
  if (!sf.camera.empty()) doc["camera"] = sf.camera;
  if (!sf.variant.empty()) doc["variant"] = sf.variant;
  if (!sf.animation.empty()) doc["animation"] = sf.animation;
  if (sf.time) doc["time"] = *sf.time;
  const ProbeVolumeSpec& pv = sf.probeVolume;
  if (pv.hasBox || pv.counts != glm::ivec3(0)) {
    json p = json::object();
    if (pv.hasBox) {
      p["min"] = {pv.min.x, pv.min.y, pv.min.z};
      p["max"] = {pv.max.x, pv.max.y, pv.max.z};
    }
    if (pv.counts != glm::ivec3(0)) p["counts"] = {pv.counts.x, pv.counts.y, pv.counts.z};
    doc["probeVolume"] = p;
  }
  doc["resolution"] = {sf.settings.width, sf.settings.height};
  json groups = {{"background", json::object()}, {"progressive", json::object()}};
  for (const SettingInfo& info : settingsSchema()) {
    const json v = settingJson(sf.settings, info);
    if (info.group.empty()) {
      doc[std::string(info.fileKey)] = v;
    } else if (info.group == "environment") {
      env[std::string(info.fileKey)] = v;
    } else if (info.group != "resolution") {
      groups[std::string(info.group)][std::string(info.fileKey)] = v;
    }
  }
  doc["environment"] = env;
  doc["background"] = groups["background"];
  doc["progressive"] = groups["progressive"];
  return doc.dump(2) + "\n";
}

Result<SceneFile> loadSceneFile(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  if (ext == ".gltf" || ext == ".glb" || ext == ".GLTF" || ext == ".GLB") {
    if (!fs::exists(path)) return makeError(path + ": no such file");
    SceneFile sf;
    sf.gltfPath = path;
    return sf;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(path + ": cannot open the scene file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parseSceneJson(ss.str(), fs::path(path).parent_path().string(), path);
}

}  // namespace penumbra
