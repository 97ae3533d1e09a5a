// Skins at rest: a still renderer shows a skinned model as its joints' node transforms pose it
// (glTF's rest pose without animation), computed once at load. The skinned vertices land in
// world space, so the skinned node's own transform does not apply (as glTF defines).
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "scene/gltf_document.h"

namespace penumbra::gltf {

Result<std::vector<glm::mat4>> inverseBindMatrices(Document& doc, int skin, LoadContext& ctx) {
  const SkinDesc& s = doc.skins[static_cast<size_t>(skin)];
  const std::string where = "skins[" + std::to_string(skin) + "]";
  std::vector<glm::mat4> out(s.joints.size(), glm::mat4(1.0f));
  if (s.inverseBindMatrices < 0) return out;
  const AccessorDesc& a = doc.accessors[static_cast<size_t>(s.inverseBindMatrices)];
  if (a.components != 16 || a.count < s.joints.size()) {
    return ctx.error(where + ".inverseBindMatrices: accessor " +
                     std::to_string(s.inverseBindMatrices) + " is " + std::to_string(a.count) +
                     " " + a.type + "; expected a MAT4 per joint (" +
                     std::to_string(s.joints.size()) + ")");
  }
  auto m = readFloats(doc, s.inverseBindMatrices, ctx, where + " inverseBindMatrices");
  if (!m.ok()) return m.error();
  for (size_t j = 0; j < s.joints.size(); ++j) out[j] = glm::make_mat4(&(*m)[16 * j]);
  return out;
}

Result<std::vector<glm::mat4>> jointMatrices(Document& doc, int skin,
                                             const std::vector<glm::mat4>& nodeWorld,
                                             LoadContext& ctx) {
  const SkinDesc& s = doc.skins[static_cast<size_t>(skin)];
  auto out = inverseBindMatrices(doc, skin, ctx);
  if (!out.ok()) return out.error();
  for (size_t j = 0; j < s.joints.size(); ++j) {
    (*out)[j] = nodeWorld[static_cast<size_t>(s.joints[j])] * (*out)[j];
  }
  return out;
}

std::vector<Rig::Node> rigNodes(const Document& doc, const std::vector<int>& parent) {
  std::vector<Rig::Node> nodes(doc.nodes.size());
  for (size_t i = 0; i < doc.nodes.size(); ++i) {
    const NodeDesc& d = doc.nodes[i];
    Rig::Node& n = nodes[i];
    n.parent = parent[i];
    n.hasMatrix = d.hasMatrix;
    n.matrix = d.local;
    n.translation = d.translation;
    n.rotation = d.rotation;
    n.scale = d.scale;
    if (d.mesh >= 0) n.weights = d.weights.value_or(doc.meshes[static_cast<size_t>(d.mesh)].weights);
  }
  return nodes;
}

void rigInstance(Rig& rig, int node, const glm::mat4& local, bool skinned) {
  rig.instanceNode.push_back(node);
  rig.instanceLocal.push_back(local);
  rig.instanceSkinned.push_back(skinned);
}

Status rigSkins(Document& doc, Rig& rig, LoadContext& ctx) {
  for (size_t s = 0; s < doc.skins.size(); ++s) {
    auto ibm = inverseBindMatrices(doc, static_cast<int>(s), ctx);
    if (!ibm.ok()) return ibm.error();
    rig.skins.push_back({doc.skins[s].joints, std::move(ibm).value()});
  }
  return {};
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
