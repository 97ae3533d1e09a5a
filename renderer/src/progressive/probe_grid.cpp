#include "progressive/probe_grid.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "progressive/probe_relocation.h"

namespace penumbra::progressive {
namespace {

// Thinner than this many cells, an axis gets two layers of probes outside the slab. A quarter
// until 2026-12-07 also caught an object on a wide floor (the dense scene: a 1.05 m rock on a
// 20 m floor, 0.21 cells), whose floor then lost the rock's occlusion: RMSE against Cycles
// 0.088 -> 0.106 at 128 frames. The reliefs it is for are 0.01-0.09 cells (the sample models'
// TextureCoordinateTest 0.09, TextureTransformTest 0.01, TextureSettingsTest 0.09).
constexpr float kThinSlab = 0.125f;

// Lays out `n` probes along one axis of `extent` from `lo`: the outer ones kProbeClearance of a
// spacing inside the bounds (half a cell left the volume's outer probes far from the walls,
// and their lookups near a wall saw the far side of the room with too much weight: the closed
// box's ceiling 18.5 % over its radiosity solution), one alone at the centre. Relocation moves a
// probe this puts inside geometry (a studio sweep's cove).
void layAxis(float lo, float extent, int n, float& spacing, float& origin) {
  if (n == 1) {
    spacing = extent;
    origin = lo + 0.5f * extent;
    return;
  }
  spacing = extent / (static_cast<float>(n - 1) + 2.0f * kProbeClearance);
  origin = lo + kProbeClearance * spacing;
}

}  // namespace

glm::ivec3 ProbeGrid::cell(int index) const {
  return {index % counts.x, (index / counts.x) % counts.y, index / (counts.x * counts.y)};
}

glm::vec3 ProbeGrid::position(int index) const {
  return origin + glm::vec3(cell(index)) * spacing;
}

int ProbeGrid::columns() const {
  return empty() ? 0 : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count()))));
}

int ProbeGrid::rows() const {
  const int c = columns();
  return c == 0 ? 0 : (count() + c - 1) / c;
}

ProbeGrid placeProbes(const Bounds& box, float density, glm::ivec3 counts) {
  ProbeGrid g;
  if (!box.valid() ||
      !std::isfinite(box.min.x + box.min.y + box.min.z + box.max.x + box.max.y + box.max.z)) {
    return g;
  }
  const glm::vec3 extent = box.max - box.min;
  const float longest = std::max(extent.x, std::max(extent.y, extent.z));
  if (!(longest > 0.0f)) return g;
  const float cellSize = longest / std::max(density, 1.0f);
  for (int a = 0; a < 3; ++a) {
    int n = counts[a] > 0 ? counts[a] : static_cast<int>(std::lround(extent[a] / cellSize));
    n = std::clamp(n, 1, 64);
    g.counts[a] = n;
    if (counts[a] <= 0 && extent[a] < kThinSlab * cellSize && extent[a] > 1e-6f * longest) {
      // A slab under an eighth of a cell thick (quads before a backdrop, a sign, a relief):
      // one layer at its centre, within an eighth of a cell of both faces, sampled the gap
      // between them and not the space its surfaces face (the plane 2.5-5 cm behind
      // TextureCoordinateTest's quads came out near black). Two layers outside it, half a
      // cell from its faces, each see one side. Thicker slabs (a row of spheres a third of a
      // cell thick, objects on a wide floor) keep their layer among their objects: the
      // material grid's, moved outside, came out 6 % further from Cycles.
      g.counts[a] = 2;
      g.spacing[a] = extent[a] + cellSize;
      g.origin[a] = box.min[a] - 0.5f * cellSize;
    } else if (extent[a] > 1e-6f * longest) {
      layAxis(box.min[a], extent[a], n, g.spacing[a], g.origin[a]);
    } else {
      // A flat axis (a ground plane alone) keeps the cell size, so biases stay finite.
      g.spacing[a] = cellSize;
      g.origin[a] = box.min[a];
    }
  }
  // Halve the densest axes until the atlas fits.
  while (g.count() > kMaxProbes) {
    int a = 0;
    for (int k = 1; k < 3; ++k) {
      if (g.counts[k] > g.counts[a]) a = k;
    }
    g.counts[a] = std::max(1, g.counts[a] / 2);
    layAxis(box.min[a], extent[a], g.counts[a], g.spacing[a], g.origin[a]);
  }
  g.diagonal = std::max(glm::length(extent), 1e-30f);
  return g;
}

std::vector<int> probesForCapture(const ProbeGrid& grid, uint64_t capture, int perCapture) {
  std::vector<int> out;
  const int n = grid.count();
  if (n == 0 || perCapture <= 0) return out;
  // A stride near n / golden ratio, made coprime with n: a permutation of 0..n-1.
  auto stride = static_cast<uint64_t>(std::max(1.0, std::round(n * 0.6180339887)));
  while (std::gcd(stride, static_cast<uint64_t>(n)) != 1) ++stride;
  const int k = std::min(perCapture, n);
  for (int j = 0; j < k; ++j) {
    const uint64_t slot =
        (capture * static_cast<uint64_t>(k) + static_cast<uint64_t>(j)) % static_cast<uint64_t>(n);
    out.push_back(static_cast<int>((slot * stride) % static_cast<uint64_t>(n)));
  }
  return out;
}

int probeCapturesThisFrame(int perFrame, int count, double meanCaptures, int frame) {
  if (count <= 0) return 0;
  const int n = std::max(perFrame, 1);
  if (meanCaptures < kProbeSettledCaptures) {
    return std::min(std::max(n, std::min((count + kProbeFillFrames - 1) / kProbeFillFrames,
                                         kProbeFillCaptures)),
                    count);
  }
  // Settled: a fractional rate, spread evenly over the frames.
  const double rate = std::min(static_cast<double>(std::max(1, n / 2)), count / 32.0);
  const double f = std::max(frame, 1);
  return static_cast<int>(std::floor(rate * f) - std::floor(rate * (f - 1.0)));
}

bool remakeProbeCache(int framesSince, double meanCaptures) {
  if (framesSince < 0) return true;
  return framesSince >= (meanCaptures < kProbeSettledCaptures ? 2 : kProbeCacheInterval);
}

}  // namespace penumbra::progressive
