// EXT_mesh_gpu_instancing: a node's mesh drawn once per instance, each with its own TRANSLATION,
// ROTATION and SCALE applied before the node's transform. The loader turns the instances into
// scene instances (one per copy), so every pass (shadow maps, probe captures, the prepass)
// draws them like any other, and the scene's bounds and framing include them all.
#include <glm/gtc/quaternion.hpp>

#include "scene/gltf_document.h"

namespace penumbra::gltf {
namespace {

// An instancing attribute's values (count * components floats), after checking its type:
// VEC3 float (TRANSLATION, SCALE), VEC4 float or normalized (u)byte/(u)short (ROTATION).
Result<std::vector<float>> attribute(Document& doc, int accessor, const char* name, int components,
                                     bool normalizedOk, const std::string& where,
                                     LoadContext& ctx) {
  const AccessorDesc& a = doc.accessors[static_cast<size_t>(accessor)];
  const bool isFloat = a.componentType == 5126;
  if (a.components != components || (!isFloat && !(normalizedOk && a.normalized))) {
    return ctx.error(where + "." + name + ": accessor " + std::to_string(accessor) + " is " +
                     a.type +
                     (isFloat        ? " float"
                      : a.normalized ? " normalized"
                                     : " integer") +
                     "; expected " + (components == 3 ? "VEC3" : "VEC4") + " float" +
                     (normalizedOk ? " or normalized" : ""));
  }
  return readFloats(doc, accessor, ctx, where + " " + name);
}

}  // namespace

Result<std::vector<glm::mat4>> instanceTransforms(Document& doc, const NodeDesc& node,
                                                  int nodeIndex, LoadContext& ctx) {
  const std::string where = "nodes[" + std::to_string(nodeIndex) + "] EXT_mesh_gpu_instancing";
  const int accessors[3] = {node.instanceTranslation, node.instanceRotation, node.instanceScale};
  const char* names[3] = {"TRANSLATION", "ROTATION", "SCALE"};
  int64_t count = -1;
  for (int i = 0; i < 3; ++i) {
    if (accessors[i] < 0) continue;
    const auto n = static_cast<int64_t>(doc.accessors[static_cast<size_t>(accessors[i])].count);
    if (count >= 0 && n != count) {
      return ctx.error(where + ": " + names[i] + " has " + std::to_string(n) +
                       " instances, another attribute " + std::to_string(count));
    }
    count = n;
  }
  if (count < 0) {
    ctx.warn(where + ": no TRANSLATION, ROTATION or SCALE; drawn once, untransformed");
    return std::vector<glm::mat4>{glm::mat4(1.0f)};
  }
  if (static_cast<uint64_t>(count) > kMaxInstances) {
    return ctx.error(where + ": " + std::to_string(count) + " instances, more than the " +
                     std::to_string(kMaxInstances) + " a node may have");
  }
  // A scene instance and at least one draw item each (gpu/gpu_scene.h): about 256 bytes.
  PN_TRY(ctx.reserve(static_cast<uint64_t>(count) * 256,
                     where + " (" + std::to_string(count) + " instances)"));
  std::vector<float> values[3];  // translation, rotation, scale
  for (int i = 0; i < 3; ++i) {
    if (accessors[i] < 0) continue;
    auto v = attribute(doc, accessors[i], names[i], i == 1 ? 4 : 3, i == 1, where, ctx);
    if (!v.ok()) return v.error();
    values[i] = std::move(v).value();
  }
  const std::vector<float>&t = values[0], &r = values[1], &s = values[2];
  std::vector<glm::mat4> out(static_cast<size_t>(count));
  for (size_t i = 0; i < out.size(); ++i) {
    glm::mat4 m(1.0f);
    if (!r.empty()) {
      // (x, y, z, w) in the file; glm::quat takes w first.
      glm::quat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);
      const float len = glm::length(q);
      m = glm::mat4_cast(len > 0.0f ? q / len : glm::quat(1, 0, 0, 0));
    }
    if (!s.empty()) {
      m[0] *= s[3 * i];
      m[1] *= s[3 * i + 1];
      m[2] *= s[3 * i + 2];
    }
    if (!t.empty()) m[3] = glm::vec4(t[3 * i], t[3 * i + 1], t[3 * i + 2], 1.0f);
    out[i] = m;
  }
  return out;
}

}  // namespace penumbra::gltf
