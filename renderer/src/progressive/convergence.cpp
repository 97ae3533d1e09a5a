#include "progressive/convergence.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "progressive/distributor.h"

namespace penumbra::progressive {

ConvergenceEstimate summarizeTiles(std::span<const float> tileRms, double threshold, int frame) {
  ConvergenceEstimate e;
  e.frame = frame;
  if (tileRms.empty()) return e;
  e.measured = true;
  std::vector<float> sorted(tileRms.begin(), tileRms.end());
  // A NaN tile never counts as converged.
  double squares = 0.0;
  for (float& v : sorted) {
    if (!std::isfinite(v)) v = INFINITY;
    squares += static_cast<double>(v) * v;
  }
  e.error = std::sqrt(squares / static_cast<double>(sorted.size()));
  const double tileBound = kTileFactor * threshold;
  const auto under =
      std::count_if(sorted.begin(), sorted.end(), [&](float v) { return v < tileBound; });
  e.convergedTiles = static_cast<double>(under) / static_cast<double>(sorted.size());
  const size_t k = std::min(sorted.size() - 1,
                            static_cast<size_t>(std::ceil(kConvergedFraction * sorted.size())) - 1);
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(k), sorted.end());
  e.tileError = sorted[k];
  e.converged = e.error < threshold && e.tileError < tileBound;
  return e;
}

float pooledError(float rms, float previousRms) {
  if (!(previousRms >= 0.0f) || !std::isfinite(previousRms)) return rms;
  return std::sqrt(0.5f * (rms * rms + 0.5f * previousRms * previousRms));
}

bool TileSkip::update(const TileChanges& changes, double threshold, int frame) {
  const size_t n = changes.rms.size();
  if (n == 0 || changes.max.size() != n) return false;
  if (mask_.size() != n) {
    mask_.assign(n, 0);
    frozen_.assign(n, 0.0f);
    skipped_ = 0;
  }
  if (frame < kSkipFromFrame) return false;
  bool added = false;
  for (size_t i = 0; i < n; ++i) {
    const float r = changes.rms[i], m = changes.max[i];
    // (NaN compares false: a tile that is not finite keeps being shaded.)
    if (mask_[i] || !(r < kSkipFactor * threshold) || !(m < kSkipPixelFactor * threshold)) {
      continue;
    }
    mask_[i] = 1;
    frozen_[i] = r;
    ++skipped_;
    added = true;
  }
  return added;
}

std::vector<float> TileSkip::effective(std::span<const float> rms) const {
  std::vector<float> out(rms.begin(), rms.end());
  if (mask_.size() != out.size()) return out;
  for (size_t i = 0; i < out.size(); ++i) {
    if (mask_[i]) out[i] = frozen_[i];
  }
  return out;
}

int expectedFrames(const ConvergenceEstimate& e, double threshold, int cap) {
  if (!e.measured || threshold <= 0.0) return cap;
  if (e.converged) return std::min(e.frame, cap);
  const double ratio = std::max(e.error / threshold, e.tileError / (kTileFactor * threshold));
  const double need = std::isfinite(ratio) ? e.frame * ratio * ratio : static_cast<double>(cap);
  int n = kFirstBlockFrames;
  while (n < need && n < cap) n *= 2;
  return std::min(std::max(n, 2 * e.frame), cap);
}

}  // namespace penumbra::progressive
