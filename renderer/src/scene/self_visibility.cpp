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
  // Every placed primitive's vertices in world space, transformed once; its triangles index
  // them from `first`.
  struct Placed {
    const Primitive* primitive;
    size_t first;
    float facing;  // -1: a mirroring transform turns the front faces clockwise (glTF)
  };
  std::vector<glm::vec3> vertices;
  std::vector<Placed> placed;
  for (const Instance& inst : scene.instances) {
    if (inst.mesh < 0 || inst.mesh >= static_cast<int>(scene.meshes.size())) continue;
    const float facing = glm::determinant(glm::mat3(inst.world)) < 0.0f ? -1.0f : 1.0f;
    for (const Primitive& p : scene.meshes[static_cast<size_t>(inst.mesh)].primitives) {
      if (vertices.size() + p.positions.size() > static_cast<size_t>(kSelfVisibilityMaxVertices)) {
        return true;
      }
      placed.push_back({&p, vertices.size(), facing});
      for (const glm::vec3& v : p.positions) {
        vertices.push_back(glm::vec3(inst.world * glm::vec4(v, 1.0f)));
      }
    }
  }
  Bounds box;
  for (const glm::vec3& v : vertices) box.extend(v);
  if (!box.valid()) return false;  // no geometry: nothing to see
  // On the plane within a ten-thousandth of the scene's size (rounding in the transforms).
  const float size = glm::length(box.max - box.min);
  if (!std::isfinite(size)) return true;
  const float eps = 1e-4f * std::max(size, 1e-6f);
  for (const Placed& pl : placed) {
    const Primitive& p = *pl.primitive;
    const bool twoSided = doubleSided(scene, p);
    for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
      if (std::max({p.indices[t], p.indices[t + 1], p.indices[t + 2]}) >= p.positions.size()) {
        return true;  // not a triangle this test can place: assume the worst
      }
      const glm::vec3& a = vertices[pl.first + p.indices[t]];
      const glm::vec3& b = vertices[pl.first + p.indices[t + 1]];
      const glm::vec3& c = vertices[pl.first + p.indices[t + 2]];
      const glm::vec3 cr = glm::cross(b - a, c - a);
      const float len = glm::length(cr);
      // A sliver (height under eps, like a UV sphere's triangles at its poles) has no plane to
      // speak of and covers nothing.
      const float longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
      if (!(len > eps * longest)) continue;
      const glm::vec3 n = cr * (pl.facing / len);
      for (const glm::vec3& v : vertices) {
        const float s = glm::dot(n, v - a);
        if (s > eps || (twoSided && s < -eps)) return true;
      }
    }
  }
  return false;
}

}  // namespace penumbra
