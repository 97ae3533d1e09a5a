// The packed single-file environment (see environment_format.h and
// docs/environment-format.md). The manifest is parsed without exceptions (the wasm build has
// none): every field is type-checked before it is read.
#include "penumbra/environment_format.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "image/image_internal.h"
#include "image/rgbe.h"
#include "ibl/sampling.h"

namespace penumbra {
namespace {

using Json = nlohmann::ordered_json;

// dump() throws on invalid UTF-8 (say, in a generator string) unless told to replace it.
std::string dumpJson(const Json& j, int indent = -1) {
  return j.dump(indent, ' ', false, Json::error_handler_t::replace);
}


int maxMipCount(int faceSize) {
  int count = 1;
  while ((faceSize >> count) > 0) ++count;
  return count;
}

Status checkEnvironment(const PackedEnvironment& env) {
  const ibl::Cubemap& cube = env.specular;
  if (!ibl::isPowerOfTwo(cube.size) || cube.size > 16384) {
    return makeError("face size must be a power of two up to 16384, got " +
                     std::to_string(cube.size));
  }
  if (cube.mipCount() < 1 || cube.mipCount() > maxMipCount(cube.size)) {
    return makeError("invalid mip count " + std::to_string(cube.mipCount()));
  }
  if (static_cast<int>(env.roughness.size()) != cube.mipCount()) {
    return makeError("roughness list has " + std::to_string(env.roughness.size()) +
                     " entries for " + std::to_string(cube.mipCount()) + " mips");
  }
  for (int m = 0; m < cube.mipCount(); ++m) {
    for (int f = 0; f < ibl::kFaceCount; ++f) {
      const Image& face = cube.face(m, f);
      const int n = cube.faceSize(m);
      if (face.width != n || face.height != n || face.channels < 3 ||
          face.pixels.size() != static_cast<size_t>(n) * n * face.channels) {
        return makeError("face " + std::string(ibl::faceName(f)) + " of mip " + std::to_string(m) +
                         " is not " + std::to_string(n) + "x" + std::to_string(n) + " RGB");
      }
    }
  }
  return {};
}

Json manifest(const PackedEnvironment& env) {
  const ibl::Cubemap& cube = env.specular;
  Json j;
  j["format"] = kPackedFormatName;
  // Version 2 adds the sun; a file without one stays version 1, readable by older readers.
  j["version"] = env.sun ? kPackedFormatVersion : 1;
  j["encoding"] = "rgbe";
  j["width"] = ibl::kFaceCount * cube.size;
  j["height"] = packedHeight(cube.size, cube.mipCount());
  j["faceSize"] = cube.size;
  j["mipCount"] = cube.mipCount();
  j["faceOrder"] = Json::array({"+X", "-X", "+Y", "-Y", "+Z", "-Z"});
  j["orientation"] = "gl-cubemap";
  j["frame"] = "gltf-y-up";
  j["layout"] = "faces-left-to-right-mips-stacked";
  j["roughnessMapping"] = "perceptual roughness r = mip / (mipCount - 1), GGX alpha = r^2";
  Json mips = Json::array();
  for (int m = 0; m < cube.mipCount(); ++m) {
    mips.push_back({{"level", m},
                    {"size", cube.faceSize(m)},
                    {"x", 0},
                    {"y", packedMipRow(cube.size, m)},
                    {"roughness", env.roughness[m]}});
  }
  j["mips"] = std::move(mips);
  j["roughness"] = env.roughness;
  j["samples"] = env.samples;
  Json coefficients = Json::array();
  for (const glm::vec3& c : env.sh.c) coefficients.push_back({c.x, c.y, c.z});
  j["sh"] = {{"convention", "radiance"},
             {"irradiance", "E(n) = sum_l A_l sum_m L_lm Y_lm(n), A = (pi, 2pi/3, pi/4)"},
             {"coefficients", std::move(coefficients)}};
  if (env.sun) {
    const ibl::Sun& sun = *env.sun;
    j["sun"] = {{"direction", {sun.direction.x, sun.direction.y, sun.direction.z}},
                {"angularRadius", sun.angularRadius},
                {"irradiance", {sun.irradiance.x, sun.irradiance.y, sun.irradiance.z}},
                {"threshold", sun.threshold}};
  }
  j["generator"] = env.generator;
  return j;
}

// Type-checked accessors: no nlohmann call below can throw.
const Json* field(const Json& j, const char* key) {
  if (!j.is_object()) return nullptr;
  auto it = j.find(key);
  return it == j.end() ? nullptr : &*it;
}
bool getInt(const Json& j, const char* key, int& out) {
  const Json* v = field(j, key);
  if (!v || !v->is_number_integer()) return false;
  const int64_t value = v->get<int64_t>();
  if (value < INT32_MIN || value > INT32_MAX) return false;
  out = static_cast<int>(value);
  return true;
}
bool getFloat(const Json& v, float& out) {
  if (!v.is_number()) return false;
  out = v.get<float>();
  return true;
}

}  // namespace

int packedMipRow(int faceSize, int mip) {
  int row = 0;
  for (int m = 0; m < mip; ++m) row += std::max(1, faceSize >> m);
  return row;
}

int packedHeight(int faceSize, int mipCount) {
  return packedMipRow(faceSize, mipCount);
}

Result<std::string> packedManifestJson(const PackedEnvironment& env) {
  PN_TRY(checkEnvironment(env));
  return dumpJson(manifest(env));
}

Result<std::vector<uint8_t>> encodePackedEnvironment(const PackedEnvironment& env) {
  PN_TRY(checkEnvironment(env));
  const ibl::Cubemap& cube = env.specular;
  Image packed(ibl::kFaceCount * cube.size, packedHeight(cube.size, cube.mipCount()), 3);
  for (int m = 0; m < cube.mipCount(); ++m) {
    const int n = cube.faceSize(m);
    const int row0 = packedMipRow(cube.size, m);
    for (int f = 0; f < ibl::kFaceCount; ++f) {
      const Image& face = cube.face(m, f);
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          const float* src = face.pixel(x, y);
          float* dst = packed.pixel(f * n + x, row0 + y);
          dst[0] = src[0];
          dst[1] = src[1];
          dst[2] = src[2];
        }
      }
    }
  }
  const std::string lines[] = {
      "# Penumbra packed environment: 6 cube faces x all mips, see docs/environment-format.md",
      std::string(kPackedHeaderKey) + "=" + dumpJson(manifest(env))};
  return rgbe::encodeFile(packed, lines);
}

Status writePackedEnvironment(const std::string& path, const PackedEnvironment& env) {
  auto bytes = encodePackedEnvironment(env);
  if (!bytes) return makeError("cannot write '" + path + "': " + bytes.message());
  PN_TRY(detail::writeFileAtomic(path, *bytes));
  const std::string json = dumpJson(manifest(env), 2) + "\n";
  const std::string jsonPath = std::filesystem::path(path).replace_extension(".json").string();
  return detail::writeFileAtomic(
      jsonPath, std::span(reinterpret_cast<const uint8_t*>(json.data()), json.size()));
}

Result<PackedEnvironment> readPackedEnvironment(const std::string& path) {
  auto bytes = detail::readFileBytes(path);
  if (!bytes) return bytes.error();
  return readPackedEnvironmentFromMemory(*bytes, path);
}

Result<PackedEnvironment> readPackedEnvironmentFromMemory(std::span<const uint8_t> bytes,
                                                          const std::string& nameForErrors) {
  const std::string where = "cannot read '" + nameForErrors + "': ";
  auto decoded = rgbe::decodeFile(bytes, nameForErrors);
  if (!decoded) return decoded.error();
  const std::string prefix = std::string(kPackedHeaderKey) + "=";
  const std::string* manifestText = nullptr;
  for (const std::string& line : decoded->headerLines) {
    if (line.rfind(prefix, 0) == 0) manifestText = &line;
  }
  if (!manifestText) {
    return makeError(where + "not a Penumbra packed environment (no " + prefix + " header line)");
  }
  const Json j = Json::parse(manifestText->substr(prefix.size()), nullptr, false);
  if (j.is_discarded() || !j.is_object()) return makeError(where + "manifest is not valid JSON");
  const Json* format = field(j, "format");
  if (!format || !format->is_string() || format->get<std::string>() != kPackedFormatName) {
    return makeError(where + "manifest format is not '" + kPackedFormatName + "'");
  }
  int version = 0;
  if (!getInt(j, "version", version) || version < 1) {
    return makeError(where + "manifest has no valid version");
  }
  if (version > kPackedFormatVersion) {
    return makeError(where + "format version " + std::to_string(version) +
                     " is newer than this reader (" + std::to_string(kPackedFormatVersion) + ")");
  }
  const Json* encoding = field(j, "encoding");
  if (!encoding || !encoding->is_string() || encoding->get<std::string>() != "rgbe") {
    return makeError(where + "unsupported encoding (expected \"rgbe\")");
  }
  int faceSize = 0;
  int mipCount = 0;
  if (!getInt(j, "faceSize", faceSize) || !ibl::isPowerOfTwo(faceSize) || faceSize > 16384) {
    return makeError(where + "manifest faceSize must be a power of two up to 16384");
  }
  if (!getInt(j, "mipCount", mipCount) || mipCount < 1 || mipCount > maxMipCount(faceSize)) {
    return makeError(where + "manifest mipCount is missing or out of range");
  }
  const Image& image = decoded->image;
  if (image.width != ibl::kFaceCount * faceSize ||
      image.height != packedHeight(faceSize, mipCount)) {
    return makeError(where + "image is " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + " but the manifest needs " +
                     std::to_string(ibl::kFaceCount * faceSize) + "x" +
                     std::to_string(packedHeight(faceSize, mipCount)));
  }
  PackedEnvironment env;
  const Json* roughness = field(j, "roughness");
  if (!roughness || !roughness->is_array() || static_cast<int>(roughness->size()) != mipCount) {
    return makeError(where + "manifest roughness must list one value per mip");
  }
  for (const Json& r : *roughness) {
    float value = 0.0f;
    if (!getFloat(r, value)) return makeError(where + "manifest roughness must be numbers");
    env.roughness.push_back(value);
  }
  const Json* sh = field(j, "sh");
  const Json* coefficients = sh ? field(*sh, "coefficients") : nullptr;
  if (!coefficients || !coefficients->is_array() || coefficients->size() != 9) {
    return makeError(where + "manifest sh.coefficients must hold 9 RGB triples");
  }
  for (int i = 0; i < 9; ++i) {
    const Json& c = (*coefficients)[i];
    if (!c.is_array() || c.size() != 3 || !getFloat(c[0], env.sh.c[i].x) ||
        !getFloat(c[1], env.sh.c[i].y) || !getFloat(c[2], env.sh.c[i].z)) {
      return makeError(where + "manifest sh.coefficients must hold 9 RGB triples");
    }
  }
  if (!getInt(j, "samples", env.samples)) env.samples = 0;
  if (const Json* sun = field(j, "sun"); sun && version >= 2) {
    ibl::Sun s;
    const Json* d = field(*sun, "direction");
    const Json* e = field(*sun, "irradiance");
    const bool ok = d && d->is_array() && d->size() == 3 && e && e->is_array() &&
                    e->size() == 3 && getFloat((*d)[0], s.direction.x) &&
                    getFloat((*d)[1], s.direction.y) && getFloat((*d)[2], s.direction.z) &&
                    getFloat((*e)[0], s.irradiance.x) && getFloat((*e)[1], s.irradiance.y) &&
                    getFloat((*e)[2], s.irradiance.z) && field(*sun, "angularRadius") &&
                    getFloat(*field(*sun, "angularRadius"), s.angularRadius);
    const float len = glm::length(s.direction);
    if (!ok || !(len > 0.5f && len < 2.0f) || !(s.angularRadius > 0.0f && s.angularRadius < 1.0f) ||
        !(s.irradiance.x >= 0.0f && s.irradiance.y >= 0.0f && s.irradiance.z >= 0.0f) ||
        !std::isfinite(s.irradiance.x + s.irradiance.y + s.irradiance.z)) {
      return makeError(where + "manifest sun needs a direction, an angularRadius in (0, 1) "
                               "radians and a finite, non-negative irradiance");
    }
    s.direction /= len;
    if (const Json* t = field(*sun, "threshold")) getFloat(*t, s.threshold);
    env.sun = s;
  }
  if (const Json* g = field(j, "generator"); g && g->is_string())
    env.generator = g->get<std::string>();

  env.specular = ibl::Cubemap(faceSize, mipCount);
  for (int m = 0; m < mipCount; ++m) {
    const int n = env.specular.faceSize(m);
    const int row0 = packedMipRow(faceSize, m);
    for (int f = 0; f < ibl::kFaceCount; ++f) {
      Image& face = env.specular.face(m, f);
      for (int y = 0; y < n; ++y) {
        const float* src = image.pixel(f * n, row0 + y);
        std::copy(src, src + static_cast<size_t>(n) * 3, face.pixel(0, y));
      }
    }
  }
  return env;
}

}  // namespace penumbra
