// Measured convergence of an automatic view (ProgressiveSettings::frames 0). At each checkpoint
// N of the plan (progressive/distributor.h: block ends about 2^(1/4) apart, where the running
// mean is a complete estimate) the renderer measures, per 8x8 tile, the RMS change of the
// displayed image (8-bit steps) since a kept earlier checkpoint M, the one nearest N/2
// (comparisonCheckpoint). With I_N = (M I_M + (N - M) B) / N for B the mean of frames M+1..N,
// Var(I_N - I_M) = Var(I_N) (N - M) / M for independent frames, so the change times
// sqrt(M / (N - M)) (changeScale) estimates the standard error of the image shown now; at
// M = N/2 the factor is 1, and for a bias that falls as 1/N (a mean still holding the first
// frames of a filling probe volume, stratified anti-aliasing) the change from N/2 is that bias.
// Each tile's estimate is taken as it is, not pooled with earlier ones: the oracle measures one
// realization of the image, whose tiles scatter as much as their changes do. The view has
// converged when the RMS of those estimates over the image is under the threshold and 99 % of
// the tiles are under three times the threshold (no region left visibly noisy: edges, whose
// coverage converges as N^-3/4, keep single tiles over it longest). At the default threshold of
// one 8-bit step that is the stopping oracle's criterion (tools/oracle). GL-free; the renderer
// draws the tiles (glsl/convergence.frag).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace penumbra::progressive {

inline constexpr int kConvergenceTile = 8;          // pixels a side
inline constexpr double kConvergedFraction = 0.99;  // of the tiles
inline constexpr double kTileFactor = 3.0;          // their bound, times the threshold

// Adaptive frames: from checkpoint kSkipFromFrame on, a tile whose RMS change is under
// kSkipFactor times the threshold and whose largest single change (a channel of one pixel) is
// under kSkipPixelFactor times it stops being shaded; the rest of the view's frames go to the
// tiles still changing (penumbrae, glossy reflections, edges). The remaining error of a tile so
// frozen is about its last change (which estimates its standard error, or a 1/N bias's rest),
// half an 8-bit step at the default threshold: no seam shows.
inline constexpr double kSkipFactor = 0.5;
inline constexpr double kSkipPixelFactor = 2.0;
inline constexpr int kSkipFromFrame = 32;

// A checkpoint's measurement, per tile: the RMS change and the largest change, 8-bit steps,
// against the image of checkpoint `against` (0: none was kept, nothing measured).
struct TileChanges {
  std::vector<float> rms;
  std::vector<float> max;
  int against = 0;
};

// Earlier checkpoints' images the renderer keeps for the comparison: with checkpoints 2^(1/4)
// apart, the fourth before N is N/2.
inline constexpr int kKeptCheckpoints = 4;

// Of the kept checkpoints (`kept`, frames, any order; 0 for an empty slot), the one to compare
// checkpoint `frame` with: the nearest to frame / 2 in ratio among those from 2 to frame - 1.
// 0 when none is.
int comparisonCheckpoint(int frame, std::span<const int> kept);
// The factor that turns the change from checkpoint `against` to `frame` into the standard
// error of the image at `frame`: sqrt(against / (frame - against)).
double changeScale(int frame, int against);

// The rate at which a measure falls, as the exponent a of N^-a: the least-squares slope of
// log(value) against log(frame) over `trend` (checkpoints, oldest first; the last kTrendPoints
// count), drawn towards kDecayPrior while fewer than five points carry it (early checkpoints'
// estimates are noisy). Clamped to [0.5, 1]: independent noise falls as N^-1/2, stratified
// sampling and a filling volume's bias as N^-1. The prior, 0.75, is where the evaluation scenes'
// estimates fall between frames 8 and 200 (tools/oracle --trace: 0.6 to 0.85).
inline constexpr size_t kTrendPoints = 8;
inline constexpr double kDecayPrior = 0.75;
struct TrendPoint {
  int frame = 0;
  double value = 0.0;
};
double decayRate(std::span<const TrendPoint> trend);

// A margin on the change from N/2 to N, kept as a measured constant. 1.1 until the probe
// volume's per-view cache was remade every 8 frames: a stale remake was an error the change
// hardly saw, which the image at the cap no longer had. With it gone, 1.0 stops 11 of 13 views
// within [1.0, 1.3] of their oracle frames, 1.1 five (tools/oracle's replay, 320x180;
// docs/decisions/2026-12-07-probe-cache-remakes.md).
inline constexpr double kChangeMargin = 1.0;
// A tile's estimated error (its change scaled to the error, in 8-bit steps) as the displayed
// 8-bit image shows it: times kChangeMargin, with the variance of two roundings to 8 bits
// (1/6 of a step squared: the image now and the final one) added.
float displayedError(double estimate);
// The inverse, for how the error falls: displayedError without the rounding (never below a
// hundredth of a step).
double withoutRounding(double displayed);

// The tiles an automatic view no longer shades, kept by the controller. A skipped tile stays
// skipped until the view restarts; its change at the checkpoint that froze it stands in for
// its (zero) change afterwards, so the view's estimate stays the error of the image shown.
// Which tiles skip is decided on the checkpoint's own change (the stricter measure).
class TileSkip {
 public:
  void reset() { *this = {}; }
  // Adds the tiles converged at checkpoint `frame` (by their changes, scaled to errors), each
  // standing in from now on with its error as shown (`shown`, displayedError; the change where
  // empty). True when any was added.
  bool update(const TileChanges& changes, double threshold, int frame,
              std::span<const float> shown = {});
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
  double decay = 0.5;           // the error falls as N^-decay over the last checkpoints
  double tileDecay = 0.5;       // and the tiles' 99th percentile as N^-tileDecay
};

// The estimate from the tiles' RMS changes at checkpoint `frame`.
ConvergenceEstimate summarizeTiles(std::span<const float> tileRms, double threshold, int frame);

// The frame at which the view is expected to converge: the first checkpoint of the plan
// (autoCheckpoints) after N, at most `cap`, at which the error and the tiles', falling at their
// measured rates (decay, tileDecay: independent noise 1/2, stratified terms and a filling
// volume's bias up to 1) and by what is left to change before the cap (sqrt(1 - c / cap), as the
// estimate counts it), are under threshold and kTileFactor threshold (each without the 8-bit
// rounding, which does not fall).
// Without a measurement: `cap`.
int expectedFrames(const ConvergenceEstimate& e, double threshold, int cap);

}  // namespace penumbra::progressive
