// mesh_lod.h's simplifier natively: Debian's meshoptimizer.
#include <meshoptimizer.h>

#include "scene/mesh_lod.h"

namespace penumbra {

bool hasSimplifier() {
  return true;
}

namespace backend {

std::vector<uint32_t> simplify(std::span<const uint32_t> indices,
                               std::span<const glm::vec3> positions, size_t targetIndexCount,
                               float targetError) {
  std::vector<uint32_t> out(indices.size());
  const size_t n = meshopt_simplify(out.data(), indices.data(), indices.size(),
                                    &positions.data()->x, positions.size(), sizeof(glm::vec3),
                                    targetIndexCount, targetError, 0, nullptr);
  out.resize(n);
  return out;
}

}  // namespace backend
}  // namespace penumbra
