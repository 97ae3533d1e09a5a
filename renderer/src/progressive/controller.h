// ProgressiveController: owns the frame counter, the sample plan and invalidation, apart from
// the renderer. It asks a FrameRenderer (the real renderer, or a mock in tests) to draw frame
// n of the plan; a camera, scene or setting change restarts at frame 1. A frame may be drawn in
// parts (stepPart): the counter advances only when its last part is done, so frame n stays
// frame n of the plan however it was split. An automatic view (frames 0) asks the renderer to
// measure its image at each checkpoint of the plan and stops once it has converged
// (progressive/convergence.h), or at maxFrames.
#pragma once

#include <span>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/frame_plan.h"
#include "penumbra/settings.h"
#include "progressive/convergence.h"
#include "progressive/distributor.h"

namespace penumbra::progressive {

class FrameRenderer {
 public:
  virtual ~FrameRenderer() = default;
  // Draws and accumulates one intermediate frame. Frame 1 restarts the accumulation.
  virtual Status renderFrame(const FramePlan& plan) = 0;
  // Draws the next part of `plan` (`begin`: its first part; anything left of an earlier frame
  // is dropped) and says whether the frame is complete. By default one part is the whole frame.
  virtual Result<bool> renderFramePart(const FramePlan& plan, bool begin) {
    (void)begin;
    PN_TRY(renderFrame(plan));
    return true;
  }
  // At a checkpoint of an automatic view, after its frame is complete: the RMS and the largest
  // change of the displayed image per tile, in 8-bit steps, since the kept checkpoint of this
  // view that comparisonCheckpoint picks (empty when none is kept); the renderer keeps this
  // checkpoint's image among the last kKeptCheckpoints.
  virtual Result<TileChanges> measureTiles(int frame) {
    (void)frame;
    return TileChanges{};
  }
  // From now until the view restarts, leaves the tiles of `mask` (TileSkip::mask) as they are:
  // later frames neither shade nor accumulate them.
  virtual Status skipTiles(std::span<const uint8_t> mask) {
    (void)mask;
    return {};
  }
};

// What stepPart() did: the frame it worked on (0 once converged) and whether that frame is now
// complete (accumulated).
struct PartStep {
  int frame = 0;
  bool done = true;
};

class Controller {
 public:
  explicit Controller(const ProgressiveSettings& settings = {}) : settings_(settings) {}

  // Each of these restarts at frame 1 when it changes anything.
  void setSettings(const ProgressiveSettings& settings);
  void setLights(const std::vector<LightInfo>& lights);
  // The scene's own lights carry it: frame 1 evaluates each from its centre, the rest start at
  // frame 2 instead of floor(m f_d) (distributeSamples).
  void setFirstLight(bool firstLight);
  // The camera or the scene changed: restart (the plan itself stays the same).
  void invalidate() { restart(); }

  // Renders the next frame unless converged (the rest of it when one is in progress). Returns
  // the frame rendered (0 if converged).
  Result<int> step(FrameRenderer& renderer);
  // Renders the next part of the next frame unless converged.
  Result<PartStep> stepPart(FrameRenderer& renderer);
  // A frame has parts drawn but not its last one.
  bool inFrame() const { return inFrame_; }

  int framesDone() const { return next_ - 1; }
  // m, or an automatic view's cap.
  int totalFrames() const { return planFrames(settings_); }
  // Frame m is done, or an automatic view has measured itself converged (or reached its cap).
  bool converged() const { return stopped_ || next_ > planFrames(settings_); }
  bool automatic() const { return settings_.frames == 0; }
  // The last checkpoint's measurement of this view (measured false before the second).
  const ConvergenceEstimate& estimate() const { return estimate_; }
  // The tiles this view no longer shades (adaptive frames,
  // ProgressiveSettings::skipConvergedTiles).
  const TileSkip& skippedTiles() const { return skip_; }
  // When the view is expected to be done: m, or for an automatic view the estimate's
  // expectedFrames (framesDone() once converged).
  int expectedFrames() const;
  const std::vector<FramePlan>& plan();
  const ProgressiveSettings& settings() const { return settings_; }

 private:
  ProgressiveSettings settings_;
  std::vector<LightInfo> lights_;
  std::vector<FramePlan> plan_;
  bool planValid_ = false;
  bool firstLight_ = false;
  int next_ = 1;
  bool inFrame_ = false;
  bool stopped_ = false;
  ConvergenceEstimate estimate_;
  TileSkip skip_;
  std::vector<TrendPoint> errorTrend_;  // every checkpoint's estimate of this view
  std::vector<TrendPoint> tileTrend_;   // and its tiles' 99th percentile

  void restart() {
    next_ = 1;
    inFrame_ = false;
    stopped_ = false;
    estimate_ = {};
    skip_.reset();
    errorTrend_.clear();
    tileTrend_.clear();
  }
  // Frame next_ is complete: counts it and, at an automatic view's checkpoint, measures.
  Status finishFrame(FrameRenderer& renderer);
};

}  // namespace penumbra::progressive
