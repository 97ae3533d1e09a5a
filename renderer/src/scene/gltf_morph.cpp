// Morph targets at rest: a still renderer shows a model as it rests, so a mesh's default
// morph weights (mesh.weights, or its node's weights) are applied once at load. Targets carry
// displacements of POSITION, NORMAL and TANGENT (xyz); sparse accessors are read as such.
#include "scene/gltf_document.h"

namespace penumbra::gltf {

Status applyMorphTargets(Document& doc, const PrimitiveDesc& pd, const std::vector<float>& weights,
                         Primitive& prim, LoadContext& ctx, const std::string& what) {
  const size_t n = std::min(weights.size(), pd.targets.size());
  for (size_t t = 0; t < n; ++t) {
    const float w = weights[t];
    if (w == 0.0f) continue;
    for (const auto& [name, accessor] : pd.targets[t]) {
      const std::string where = what + " target " + std::to_string(t) + " " + name;
      const bool position = name == "POSITION", normal = name == "NORMAL",
                 tangent = name == "TANGENT";
      if (!position && !normal && !tangent) continue;  // e.g. TEXCOORD_0: not morphed here
      const AccessorDesc& a = doc.accessors[static_cast<size_t>(accessor)];
      if (a.components != 3) {
        return ctx.error(where + ": accessor " + std::to_string(accessor) + " is " + a.type +
                         "; expected VEC3");
      }
      if (a.count != prim.positions.size()) {
        return ctx.error(where + " has " + std::to_string(a.count) + " elements but POSITION has " +
                         std::to_string(prim.positions.size()));
      }
      auto d = readFloats(doc, accessor, ctx, where);
      if (!d.ok()) return d.error();
      const std::vector<float>& v = *d;
      for (size_t i = 0; i < prim.positions.size(); ++i) {
        const glm::vec3 delta = w * glm::vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
        if (position) {
          prim.positions[i] += delta;
        } else if (normal && !prim.normals.empty()) {
          prim.normals[i] += delta;
        } else if (tangent && !prim.tangents.empty()) {
          prim.tangents[i] += glm::vec4(delta, 0.0f);
        }
      }
    }
  }
  // Morphed normals are no longer unit length (tangents are normalised in the shader).
  for (glm::vec3& nrm : prim.normals) {
    const float len = glm::length(nrm);
    if (len > 0.0f) nrm /= len;
  }
  return {};
}

Result<std::vector<Deformation::Target>> readMorphTargets(Document& doc, const PrimitiveDesc& pd,
                                                         size_t vertexCount, LoadContext& ctx,
                                                         const std::string& what) {
  std::vector<Deformation::Target> targets(pd.targets.size());
  for (size_t t = 0; t < pd.targets.size(); ++t) {
    for (const auto& [name, accessor] : pd.targets[t]) {
      std::vector<glm::vec3>* out = name == "POSITION" ? &targets[t].positions
                                    : name == "NORMAL" ? &targets[t].normals
                                    : name == "TANGENT" ? &targets[t].tangents
                                                        : nullptr;
      if (!out) continue;
      const std::string where = what + " target " + std::to_string(t) + " " + name;
      const AccessorDesc& a = doc.accessors[static_cast<size_t>(accessor)];
      if (a.components != 3 || a.count != vertexCount) {
        return ctx.error(where + ": accessor " + std::to_string(accessor) + " is " +
                         std::to_string(a.count) + " " + a.type + "; expected a VEC3 per vertex (" +
                         std::to_string(vertexCount) + ")");
      }
      auto d = readFloats(doc, accessor, ctx, where);
      if (!d.ok()) return d.error();
      out->resize(vertexCount);
      for (size_t i = 0; i < vertexCount; ++i) {
        (*out)[i] = glm::vec3((*d)[3 * i], (*d)[3 * i + 1], (*d)[3 * i + 2]);
      }
    }
  }
  return targets;
}

}  // namespace penumbra::gltf
