// Skins at rest: a still renderer shows a skinned model as its joints' node transforms pose it
// (glTF's rest pose without animation), computed once at load. The skinned vertices land in
// world space, so the skinned node's own transform does not apply (as glTF defines).
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "scene/gltf_document.h"

namespace penumbra::gltf {

Result<std::vector<glm::mat4>> jointMatrices(Document& doc, int skin,
                                             const std::vector<glm::mat4>& nodeWorld,
                                             LoadContext& ctx) {
  const SkinDesc& s = doc.skins[static_cast<size_t>(skin)];
  const std::string where = "skins[" + std::to_string(skin) + "]";
  std::vector<float> ibm;
  if (s.inverseBindMatrices >= 0) {
    const AccessorDesc& a = doc.accessors[static_cast<size_t>(s.inverseBindMatrices)];
    if (a.components != 16 || a.count < s.joints.size()) {
      return ctx.error(where + ".inverseBindMatrices: accessor " +
                       std::to_string(s.inverseBindMatrices) + " is " + std::to_string(a.count) +
                       " " + a.type + "; expected a MAT4 per joint (" +
                       std::to_string(s.joints.size()) + ")");
    }
    auto m = readFloats(doc, s.inverseBindMatrices, ctx, where + " inverseBindMatrices");
    if (!m.ok()) return m.error();
    ibm = std::move(m).value();
  }
  std::vector<glm::mat4> out(s.joints.size(), glm::mat4(1.0f));
  for (size_t j = 0; j < s.joints.size(); ++j) {
    const glm::mat4 inverseBind = ibm.empty() ? glm::mat4(1.0f) : glm::make_mat4(&ibm[16 * j]);
    out[j] = nodeWorld[static_cast<size_t>(s.joints[j])] * inverseBind;
  }
  return out;
}

Status applySkin(const std::vector<float>& jointIndices, const std::vector<float>& weights,
                 const std::vector<glm::mat4>& joints, Primitive& prim, LoadContext& ctx,
                 const std::string& what) {
  const size_t n = prim.positions.size();
  using Named = std::pair<const char*, const std::vector<float>*>;
  for (const auto& [name, values] :
       {Named{"JOINTS_0", &jointIndices}, Named{"WEIGHTS_0", &weights}}) {
    if (values->size() != 4 * n) {
      return ctx.error(what + " " + name + ": " + std::to_string(values->size() / 4) +
                       " values; expected a VEC4 per vertex (" + std::to_string(n) + ")");
    }
  }
  for (size_t v = 0; v < n; ++v) {
    glm::mat4 m(0.0f);
    for (size_t k = 0; k < 4; ++k) {
      const float weight = weights[4 * v + k];
      if (weight == 0.0f) continue;
      const auto joint = static_cast<size_t>(jointIndices[4 * v + k]);
      if (joint >= joints.size()) {
        return ctx.error(what + " JOINTS_0: vertex " + std::to_string(v) + " names joint " +
                         std::to_string(joint) + " of a skin with " +
                         std::to_string(joints.size()));
      }
      m += weight * joints[joint];
    }
    prim.positions[v] = glm::vec3(m * glm::vec4(prim.positions[v], 1.0f));
    const glm::mat3 linear(m);
    if (!prim.normals.empty()) {
      const glm::vec3 nrm = glm::inverseTranspose(linear) * prim.normals[v];
      prim.normals[v] = glm::length(nrm) > 0.0f ? glm::normalize(nrm) : prim.normals[v];
    }
    if (!prim.tangents.empty()) {
      const glm::vec3 t = linear * glm::vec3(prim.tangents[v]);
      if (glm::length(t) > 0.0f)
        prim.tangents[v] = glm::vec4(glm::normalize(t), prim.tangents[v].w);
    }
  }
  return {};
}

}  // namespace penumbra::gltf
