#include "penumbra/scene_file.h"

#include <cstdint>
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

Status parseProgressive(const json& p, ProgressiveSettings& s, std::vector<std::string>& warnings) {
  if (!p.is_object()) return makeError("'progressive' must be an object");
  warnUnknown(p,
              {"frames", "fd", "occlusionDistance", "lightSamples", "shadowMapSize",
               "screenSpaceIndirect", "indirectClamp", "seed"},
              "progressive", warnings);
  PN_TRY(read(p, "frames", s.frames, "progressive"));
  PN_TRY(read(p, "fd", s.directDelay, "progressive"));
  PN_TRY(read(p, "occlusionDistance", s.occlusionDistance, "progressive"));
  PN_TRY(read(p, "lightSamples", s.lightSamples, "progressive"));
  PN_TRY(read(p, "shadowMapSize", s.shadowMapSize, "progressive"));
  PN_TRY(read(p, "screenSpaceIndirect", s.screenSpaceIndirect, "progressive"));
  PN_TRY(read(p, "indirectClamp", s.indirectClamp, "progressive"));
  PN_TRY(read(p, "seed", s.seed, "progressive"));
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
  warnUnknown(doc,
              {"gltf", "environment", "camera", "resolution", "exposure", "toneMapper",
               "background", "progressive", "$schema", "comment"},
              "the scene file", sf.warnings);
  auto fail = [&](const Error& e) { return makeError(name + ": " + e.message); };

  std::string gltf;
  if (auto st = read(doc, "gltf", gltf, "scene"); !st) return fail(st.error());
  if (gltf.empty()) return makeError(name + ": 'gltf' (the model to render) is missing");
  sf.gltfPath = resolve(baseDir, gltf);

  if (auto it = doc.find("environment"); it != doc.end()) {
    if (it->is_string()) {
      sf.environmentPath = resolve(baseDir, it->get<std::string>());
    } else if (it->is_object()) {
      warnUnknown(*it, {"file", "uniform", "intensity", "rotation"}, "environment", sf.warnings);
      std::string file;
      if (auto st = read(*it, "file", file, "environment"); !st) return fail(st.error());
      sf.environmentPath = resolve(baseDir, file);
      std::vector<float> uni;
      if (auto st = read(*it, "uniform", uni, "environment"); !st) return fail(st.error());
      if (!uni.empty()) {
        if (uni.size() != 3) return makeError(name + ": environment.uniform must be [r, g, b]");
        sf.uniformEnvironment = glm::vec3(uni[0], uni[1], uni[2]);
      }
      if (auto st = read(*it, "intensity", s.environmentIntensity, "environment"); !st) {
        return fail(st.error());
      }
      if (auto st = read(*it, "rotation", s.environmentRotation, "environment"); !st) {
        return fail(st.error());
      }
    } else {
      return makeError(name + ": 'environment' must be a file name or an object");
    }
  }
  if (auto it = doc.find("camera"); it != doc.end()) {
    if (it->is_string()) {
      sf.camera = it->get<std::string>();
    } else if (it->is_number_integer()) {
      sf.camera = std::to_string(it->get<int>());
    } else {
      return makeError(name + ": 'camera' must be a name or an index");
    }
  }
  if (auto it = doc.find("resolution"); it != doc.end()) {
    std::vector<int> r;
    if (auto st = read(doc, "resolution", r, "scene"); !st || r.size() != 2) {
      return makeError(name + ": 'resolution' must be [width, height]");
    }
    s.width = r[0];
    s.height = r[1];
  }
  if (auto st = read(doc, "exposure", s.exposure, "scene"); !st) return fail(st.error());
  std::string tm;
  if (auto st = read(doc, "toneMapper", tm, "scene"); !st) return fail(st.error());
  if (!tm.empty()) {
    auto t = parseToneMapper(tm);
    if (!t) return fail(t.error());
    s.toneMapper = *t;
  }
  if (auto it = doc.find("background"); it != doc.end()) {
    if (!it->is_object()) return makeError(name + ": 'background' must be an object");
    warnUnknown(*it, {"show", "blur"}, "background", sf.warnings);
    if (auto st = read(*it, "show", s.showBackground, "background"); !st) return fail(st.error());
    if (auto st = read(*it, "blur", s.backgroundBlur, "background"); !st) return fail(st.error());
  }
  if (auto it = doc.find("progressive"); it != doc.end()) {
    if (auto st = parseProgressive(*it, s.progressive, sf.warnings); !st) return fail(st.error());
  }
  if (auto st = validate(s); !st) return fail(st.error());
  return sf;
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
