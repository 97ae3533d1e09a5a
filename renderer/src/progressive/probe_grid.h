// ProbeGrid: where the irradiance probes of the probe volume sit and in which order they are
// captured. A regular grid over the scene's bounds (or the scene file's override), probes at
// cell centres so none sits on the bounding walls; its spacing follows the bounds, so a model
// in millimetres and a room in metres get the same layout. Plain data and pure functions: the
// GPU side (passes/probe_volume) only reads it.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/scene.h"

namespace penumbra::progressive {

// At most this many probes (an atlas of 64 x 64 tiles of 16 texels fits WebGL2's 4096 limit).
inline constexpr int kMaxProbes = 4096;

struct ProbeGrid {
  glm::vec3 origin{0.0f};   // centre of probe (0, 0, 0)
  glm::vec3 spacing{1.0f};  // between neighbours along each axis (> 0 even with one probe)
  glm::ivec3 counts{0};     // probes along x, y, z
  float diagonal = 1.0f;    // of the volume's box: distances in the probe maps are in this unit
  int count() const { return counts.x * counts.y * counts.z; }
  bool empty() const { return count() == 0; }
  glm::ivec3 cell(int index) const;
  glm::vec3 position(int index) const;
  // Atlas layout: probe i is tile (i % columns, i / columns).
  int columns() const;
  int rows() const;
};

// The grid for a scene box: `density` probes along the box's longest side (at least one along
// every axis, about as many per unit length on the others); `counts` > 0 on an axis overrides
// it. Empty for an invalid box.
ProbeGrid placeProbes(const Bounds& box, float density, glm::ivec3 counts = glm::ivec3(0));

// The probes the volume's capture number `capture` updates, `perCapture` of them: consecutive
// runs of a fixed permutation of all probes (a stride coprime with the count, so successive
// captures spread over the volume instead of sweeping it plane by plane). Every probe is
// captured once per count / perCapture captures.
std::vector<int> probesForCapture(const ProbeGrid& grid, uint64_t capture, int perCapture);

}  // namespace penumbra::progressive
