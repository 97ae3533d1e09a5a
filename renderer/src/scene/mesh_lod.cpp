#include "scene/mesh_lod.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

std::vector<uint32_t> captureLod(const Primitive& prim, float maxScale, float sceneDiagonal) {
  const size_t triangles = prim.indices.size() / 3;
  if (triangles < kCaptureLodMinTriangles || !prim.bounds.valid() || !hasSimplifier()) return {};
  const glm::vec3 size = prim.bounds.max - prim.bounds.min;
  const float extent = std::max(size.x, std::max(size.y, size.z));
  if (!(extent > 0.0f) || !(maxScale > 0.0f) || !(sceneDiagonal > 0.0f) ||
      !std::isfinite(extent * maxScale * sceneDiagonal)) {
    return {};
  }
  // The loader drops triangles on non-finite positions but keeps the vertices; the simplifier
  // scales by every vertex, so one NaN would void its error bound.
  for (const glm::vec3& p : prim.positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return {};
  }
  // The allowed deviation in world units, back in the mesh's own (its largest instance).
  const float relative = kCaptureLodErrorFraction * sceneDiagonal / (maxScale * extent);
  // No triangle count to aim at: the error bound alone decides.
  std::vector<uint32_t> lod = backend::simplify(prim.indices, prim.positions, 0, relative);
  if (lod.empty() || lod.size() * 4 > prim.indices.size() * 3) return {};
  return lod;
}

}  // namespace penumbra
