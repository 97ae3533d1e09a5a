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

int comparisonCheckpoint(int frame, std::span<const int> kept) {
  int best = 0;
  double bestDistance = INFINITY;
  for (const int k : kept) {
    if (k < 2 || k >= frame) continue;
    const double d = std::abs(std::log(2.0 * k / frame));
    if (d < bestDistance) {
      bestDistance = d;
      best = k;
    }
  }
  return best;
}

double changeScale(int frame, int against) {
  if (against <= 0 || against >= frame) return 1.0;
  return std::sqrt(static_cast<double>(against) / static_cast<double>(frame - against));
}

double decayRate(std::span<const TrendPoint> trend) {
  const size_t first = trend.size() > kTrendPoints ? trend.size() - kTrendPoints : 0;
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = first; i < trend.size(); ++i) {
    const TrendPoint& p = trend[i];
    if (p.frame <= 0 || !(p.value > 0.0) || !std::isfinite(p.value)) continue;
    const double x = std::log(static_cast<double>(p.frame)), y = std::log(p.value);
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double den = n * sxx - sx * sx;
  if (n < 2 || !(den > 1e-12)) return kDecayPrior;
  const double slope = -(n * sxy - sx * sy) / den;
  const double weight = std::min(1.0, (n - 1.0) / 4.0);
  return std::clamp(kDecayPrior + weight * (slope - kDecayPrior), 0.5, 1.0);
}

float displayedError(double estimate) {
  const double e = kChangeMargin * estimate;
  return static_cast<float>(std::sqrt(e * e + 1.0 / 6.0));
}

double withoutRounding(double displayed) {
  return std::sqrt(std::max(displayed * displayed - 1.0 / 6.0, 1e-4)) / kChangeMargin;
}

bool TileSkip::update(const TileChanges& changes, double threshold, int frame,
                      std::span<const float> shown) {
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
    frozen_[i] = shown.size() == n ? shown[i] : r;
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
  // What is left to change before the cap, sqrt(1 - N / cap) of the error (the estimate's own
  // factor): it falls with N too, so it is taken out at N and put back at each checkpoint.
  const auto rest = [&](double n) { return std::sqrt(std::max(0.0, 1.0 - n / cap)); };
  const double now = std::max(rest(e.frame), 1e-3);
  const auto meets = [&](double c, double value, double bound, double decay) {
    const double v = withoutRounding(value) / now *
                     std::pow(e.frame / c, std::clamp(decay, 0.5, 1.0)) * rest(c);
    return v <= withoutRounding(bound);
  };
  for (const int c : autoCheckpoints(cap)) {
    if (c <= e.frame) continue;
    if (meets(c, e.error, threshold, e.decay) &&
        meets(c, e.tileError, kTileFactor * threshold, e.tileDecay)) {
      return c;
    }
  }
  return cap;
}

}  // namespace penumbra::progressive
