// A tiny glTF writer for the scene tests: JSON (nlohmann) plus one binary buffer, serialised as
// .gltf with a base64 data: URI or as .glb bytes, so every test builds exactly the file it needs.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "penumbra/scene.h"

namespace penumbra::test {

using nlohmann::json;

constexpr int kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kUInt = 5125,
              kFloat = 5126;

inline std::string base64(const std::vector<uint8_t>& in) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const uint32_t v = (uint32_t{in[i]} << 16) | (uint32_t{in[i + 1]} << 8) | in[i + 2];
    for (int k = 3; k >= 0; --k) out.push_back(kAlphabet[(v >> (6 * k)) & 63]);
  }
  if (i < in.size()) {
    uint32_t v = uint32_t{in[i]} << 16;
    if (i + 1 < in.size()) v |= uint32_t{in[i + 1]} << 8;
    out.push_back(kAlphabet[(v >> 18) & 63]);
    out.push_back(kAlphabet[(v >> 12) & 63]);
    out.push_back(i + 1 < in.size() ? kAlphabet[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

class GltfBuilder {
 public:
  json doc = {{"asset", {{"version", "2.0"}}}};
  std::vector<uint8_t> bin;
  // When false, serialisation leaves doc["buffers"] alone (tests that write their own).
  bool autoBuffer = true;

  int push(const char* array, json object) {
    json& arr = doc[array];
    if (!arr.is_array()) arr = json::array();
    arr.push_back(std::move(object));
    return static_cast<int>(arr.size() - 1);
  }

  // Appends bytes to the binary buffer (4-byte aligned) and returns their offset.
  size_t append(const void* data, size_t size) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t offset = bin.size();
    bin.resize(offset + size);
    if (size) std::memcpy(bin.data() + offset, data, size);
    return offset;
  }

  int view(const void* data, size_t size, size_t stride = 0) {
    const size_t offset = append(data, size);
    json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}};
    if (stride) v["byteStride"] = stride;
    return push("bufferViews", v);
  }
  template <class T>
  int view(const std::vector<T>& values, size_t stride = 0) {
    return view(values.data(), values.size() * sizeof(T), stride);
  }

  int accessor(int bufferView, int componentType, size_t count, const char* type,
               bool normalized = false, size_t byteOffset = 0) {
    json a = {{"componentType", componentType}, {"count", count}, {"type", type}};
    if (bufferView >= 0) a["bufferView"] = bufferView;
    if (byteOffset) a["byteOffset"] = byteOffset;
    if (normalized) a["normalized"] = true;
    return push("accessors", a);
  }

  int vec3(const std::vector<glm::vec3>& v) {
    std::vector<float> f;
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const auto& p : v) {
      f.insert(f.end(), {p.x, p.y, p.z});
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const int a = accessor(view(f), kFloat, v.size(), "VEC3");
    doc["accessors"][static_cast<size_t>(a)]["min"] = {lo.x, lo.y, lo.z};
    doc["accessors"][static_cast<size_t>(a)]["max"] = {hi.x, hi.y, hi.z};
    return a;
  }
  int vec2(const std::vector<glm::vec2>& v) {
    std::vector<float> f;
    for (const auto& p : v) f.insert(f.end(), {p.x, p.y});
    return accessor(view(f), kFloat, v.size(), "VEC2");
  }
  int vec4(const std::vector<glm::vec4>& v) {
    std::vector<float> f;
    for (const auto& p : v) f.insert(f.end(), {p.x, p.y, p.z, p.w});
    return accessor(view(f), kFloat, v.size(), "VEC4");
  }
  int indices16(const std::vector<uint16_t>& i) {
    return accessor(view(i), kUShort, i.size(), "SCALAR");
  }
  int indices32(const std::vector<uint32_t>& i) {
    return accessor(view(i), kUInt, i.size(), "SCALAR");
  }

  int mesh(const json& primitive) { return push("meshes", {{"primitives", {primitive}}}); }
  int node(const json& n) { return push("nodes", n); }
  void scene(const std::vector<int>& roots) {
    doc["scenes"] = json::array({{{"nodes", roots}}});
    doc["scene"] = 0;
  }
  void useExtension(const std::string& name, bool required = false) {
    doc["extensionsUsed"].push_back(name);
    if (required) doc["extensionsRequired"].push_back(name);
  }

  // A unit quad in the XY plane facing +Z (two triangles), UVs with v down as in glTF.
  int quadMesh(int material = -1) {
    const int pos = vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int uv = vec2({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    const int idx = indices16({0, 1, 2, 0, 2, 3});
    json prim = {{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}, {"indices", idx}};
    if (material >= 0) prim["material"] = material;
    return mesh(prim);
  }

  json finalDoc(bool binary) const {
    json d = doc;
    if (autoBuffer && !bin.empty()) {
      json buffer = {{"byteLength", bin.size()}};
      if (!binary) buffer["uri"] = "data:application/octet-stream;base64," + base64(bin);
      d["buffers"] = json::array({buffer});
    }
    return d;
  }

  std::string gltf() const { return finalDoc(false).dump(); }

  std::vector<uint8_t> glb() const {
    std::string text = finalDoc(true).dump();
    while (text.size() % 4) text.push_back(' ');
    std::vector<uint8_t> b = bin;
    while (b.size() % 4) b.push_back(0);
    std::vector<uint8_t> out;
    auto u32 = [&](uint32_t v) {
      for (int k = 0; k < 4; ++k) out.push_back(static_cast<uint8_t>(v >> (8 * k)));
    };
    const uint32_t total =
        static_cast<uint32_t>(12 + 8 + text.size() + (b.empty() ? 0 : 8 + b.size()));
    u32(0x46546C67);
    u32(2);
    u32(total);
    u32(static_cast<uint32_t>(text.size()));
    u32(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    if (!b.empty()) {
      u32(static_cast<uint32_t>(b.size()));
      u32(0x004E4942);
      out.insert(out.end(), b.begin(), b.end());
    }
    return out;
  }

  Result<Scene> load(bool binary = false, const LoadOptions& options = {},
                     const std::string& baseDir = "") const {
    if (binary) {
      const auto bytes = glb();
      return loadGltfFromMemory(bytes, baseDir, "test.glb", options);
    }
    const std::string text = gltf();
    return loadGltfFromMemory(
        std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()),
        baseDir, "test.gltf", options);
  }
};

inline Result<Scene> loadText(const std::string& text, const std::string& name = "test.gltf",
                              const LoadOptions& options = {}) {
  return loadGltfFromMemory(
      std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()), "",
      name, options);
}

// Component-wise EXPECT_NEAR for vectors.
inline void expectNear(const glm::vec3& a, const glm::vec3& b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps) << "x";
  EXPECT_NEAR(a.y, b.y, eps) << "y";
  EXPECT_NEAR(a.z, b.z, eps) << "z";
}

inline bool hasWarning(const Scene& scene, const std::string& needle) {
  for (const auto& w : scene.warnings) {
    if (w.find(needle) != std::string::npos) return true;
  }
  return false;
}

}  // namespace penumbra::test
