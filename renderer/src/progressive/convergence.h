// Measured convergence of an automatic view (ProgressiveSettings::frames 0). At each checkpoint
// N of the plan (8, 16, 32, ...: block ends, where the running mean is a complete estimate) the
// renderer measures, per 8x8 tile, the RMS change of the displayed image (8-bit steps) since
// the previous checkpoint N/2. With I_N = (A + B) / 2 for the means A and B of the two halves,
// I_N - I_{N/2} = (B - A) / 2, whose variance is that of I_N itself: the change estimates the
// standard error of the image shown now (for a bias that falls as 1/N, such as a mean still
// holding the first frames of a filling probe volume, it is that bias). The view has converged
// when the image's RMS change is under the threshold and 99 % of its tiles are under four
// times the threshold (no region left visibly noisy: edges, whose coverage converges as
// N^-3/4, keep single tiles over it longest). GL-free; the renderer draws the tiles
// (glsl/convergence.frag).
#pragma once

#include <span>

namespace penumbra::progressive {

inline constexpr int kConvergenceTile = 8;         // pixels a side
inline constexpr double kConvergedFraction = 0.99;  // of the tiles
inline constexpr double kTileFactor = 4.0;          // their bound, times the threshold

struct ConvergenceEstimate {
  bool measured = false;    // a checkpoint had one before it in this view
  int frame = 0;            // the checkpoint
  double error = 0.0;       // the RMS change over the image, 8-bit steps
  double tileError = 0.0;   // the 99th percentile of the tiles' RMS change, 8-bit steps
  double convergedTiles = 0.0;  // fraction of tiles under kTileFactor times the threshold
  bool converged = false;   // error < threshold and tileError < kTileFactor threshold
};

// The estimate from the tiles' RMS changes at checkpoint `frame`.
ConvergenceEstimate summarizeTiles(std::span<const float> tileRms, double threshold, int frame);

// The frame at which the view is expected to converge: the error falls as 1/sqrt(N) (the
// slowest rate of its terms; stratified ones fall faster), so N r^2 for r the larger of
// error / threshold and tileError / (kTileFactor threshold),
// rounded up to a checkpoint (a power of two, kFirstBlockFrames or more) and at most `cap`.
// Without a measurement: `cap`.
int expectedFrames(const ConvergenceEstimate& e, double threshold, int cap);

}  // namespace penumbra::progressive
