// Measured convergence of an automatic view (ProgressiveSettings::frames 0). At each checkpoint
// N of the plan (8, 16, 32, ...: block ends, where the running mean is a complete estimate) the
// renderer measures, per 8x8 tile, the RMS change of the displayed image (8-bit steps) since
// the previous checkpoint N/2. With I_N = (A + B) / 2 for the means A and B of the two halves,
// I_N - I_{N/2} = (B - A) / 2, whose variance is that of I_N itself: the change estimates the
// standard error of the image shown now (for a bias that falls as 1/N, such as a mean still
// holding the first frames of a filling probe volume, it is that bias). A tile's error is
// estimated from its last two changes (pooledError: one tile's change is a noisy figure). The
// view has converged when the RMS of those estimates over the image is under the threshold and
// 99 % of the tiles are under four times the threshold (no region left visibly noisy: edges,
// whose coverage converges as N^-3/4, keep single tiles over it longest). GL-free; the
// renderer draws the tiles (glsl/convergence.frag).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace penumbra::progressive {

inline constexpr int kConvergenceTile = 8;          // pixels a side
inline constexpr double kConvergedFraction = 0.99;  // of the tiles
inline constexpr double kTileFactor = 4.0;          // their bound, times the threshold

// Adaptive frames: from checkpoint kSkipFromFrame on, a tile whose RMS change is under
// kSkipFactor times the threshold and whose largest single change (a channel of one pixel) is
// under kSkipPixelFactor times it stops being shaded; the rest of the view's frames go to the
// tiles still changing (penumbrae, glossy reflections, edges). The remaining error of a tile so
// frozen is about its last change (which estimates its standard error, or a 1/N bias's rest),
// half an 8-bit step at the default threshold: no seam shows.
inline constexpr double kSkipFactor = 0.5;
inline constexpr double kSkipPixelFactor = 2.0;
inline constexpr int kSkipFromFrame = 32;

// A checkpoint's measurement, per tile: the RMS change and the largest change, 8-bit steps.
struct TileChanges {
  std::vector<float> rms;
  std::vector<float> max;
};

// A tile's error at checkpoint N from its change since N/2 (`rms`) and the change before that
// (`previousRms`, N/4 to N/2). Each estimates the error's variance under the same 1/sqrt(N)
// law the estimate assumes throughout: rms^2 that at N, previousRms^2 that at N/2, twice as
// large. Their mean, (rms^2 + previousRms^2 / 2) / 2, has half the variance of rms^2 alone:
// one tile's change is a noisy figure (a few edge pixels carry it), and the 99th percentile of
// noisy figures sits above that of the errors they estimate. For an error falling faster than
// 1/sqrt(N) (a filling volume's 1/N bias, stratified sampling) the earlier change is the larger
// and the estimate errs high. `rms` alone where previousRms is negative or not finite.
float pooledError(float rms, float previousRms);

// The tiles an automatic view no longer shades, kept by the controller. A skipped tile stays
// skipped until the view restarts; its change at the checkpoint that froze it stands in for
// its (zero) change afterwards, so the view's estimate stays the error of the image shown.
// Which tiles skip is decided on the checkpoint's own change (the stricter measure).
class TileSkip {
 public:
  void reset() { *this = {}; }
  // Adds the tiles converged at checkpoint `frame`. True when any was added.
  bool update(const TileChanges& changes, double threshold, int frame);
  // The tiles' RMS changes with the skipped tiles' frozen ones in place.
  std::vector<float> effective(std::span<const float> rms) const;
  // A byte a tile (1: skipped), row-major from the bottom row: empty before any was skipped.
  const std::vector<uint8_t>& mask() const { return mask_; }
  int skipped() const { return skipped_; }

 private:
  std::vector<uint8_t> mask_;
  std::vector<float> frozen_;
  int skipped_ = 0;
};

struct ConvergenceEstimate {
  bool measured = false;        // a checkpoint had one before it in this view
  int frame = 0;                // the checkpoint
  double error = 0.0;           // the RMS change over the image, 8-bit steps
  double tileError = 0.0;       // the 99th percentile of the tiles' RMS change, 8-bit steps
  double convergedTiles = 0.0;  // fraction of tiles under kTileFactor times the threshold
  bool converged = false;       // error < threshold and tileError < kTileFactor threshold
  double skippedTiles = 0.0;    // fraction of tiles no longer shaded (adaptive frames)
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
