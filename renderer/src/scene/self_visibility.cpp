#include "scene/self_visibility.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace penumbra {
namespace {

bool doubleSided(const Scene& scene, const Primitive& p) {
  auto twoSided = [&](int m) {
    // The glTF default material (-1) is single-sided.
    return m >= 0 && m < static_cast<int>(scene.materials.size()) &&
           scene.materials[static_cast<size_t>(m)].doubleSided;
  };
  if (twoSided(p.material)) return true;
  return std::any_of(p.variantMaterials.begin(), p.variantMaterials.end(), twoSided);
}

}  // namespace

bool surfacesSeeEachOther(const Scene& scene) {
  std::vector<glm::vec3> vertices;
  for (const Instance& inst : scene.instances) {
    if (inst.mesh < 0 || inst.mesh >= static_cast<int>(scene.meshes.size())) continue;
    for (const Primitive& p : scene.meshes[static_cast<size_t>(inst.mesh)].primitives) {
      if (vertices.size() + p.positions.size() > static_cast<size_t>(kSelfVisibilityMaxVertices)) {
        return true;
      }
      for (const glm::vec3& v : p.positions)
        vertices.push_back(glm::vec3(inst.world * glm::vec4(v, 1.0f)));
    }
  }
  Bounds box;
  for (const glm::vec3& v : vertices) box.extend(v);
  if (!box.valid()) return false;  // no geometry: nothing to see
  // On the plane within a ten-thousandth of the scene's size (rounding in the transforms).
  const float size = glm::length(box.max - box.min);
  if (!std::isfinite(size)) return true;
  const float eps = 1e-4f * std::max(size, 1e-6f);
  for (const Instance& inst : scene.instances) {
    if (inst.mesh < 0 || inst.mesh >= static_cast<int>(scene.meshes.size())) continue;
    // A mirroring transform turns the front faces clockwise (glTF).
    const float facing = glm::determinant(glm::mat3(inst.world)) < 0.0f ? -1.0f : 1.0f;
    for (const Primitive& p : scene.meshes[static_cast<size_t>(inst.mesh)].primitives) {
      const bool twoSided = doubleSided(scene, p);
      for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        if (std::max({p.indices[t], p.indices[t + 1], p.indices[t + 2]}) >= p.positions.size()) {
          return true;  // not a triangle this test can place: assume the worst
        }
        const auto world = [&](size_t k) {
          return glm::vec3(inst.world * glm::vec4(p.positions[p.indices[t + k]], 1.0f));
        };
        const glm::vec3 a = world(0), b = world(1), c = world(2);
        const glm::vec3 cr = glm::cross(b - a, c - a);
        const float len = glm::length(cr);
        // A sliver (height under eps, like a UV sphere's triangles at its poles) has no plane
        // to speak of and covers nothing.
        const float longest =
            std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
        if (!(len > eps * longest)) continue;
        const glm::vec3 n = cr * (facing / len);
        for (const glm::vec3& v : vertices) {
          const float s = glm::dot(n, v - a);
          if (s > eps || (twoSided && s < -eps)) return true;
        }
      }
    }
  }
  return false;
}

}  // namespace penumbra
