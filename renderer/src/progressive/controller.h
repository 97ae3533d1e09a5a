// ProgressiveController: owns the frame counter, the sample plan and invalidation, apart from
// the renderer. It asks a FrameRenderer (the real renderer, or a mock in tests) to draw frame
// n of the plan; a camera, scene or setting change restarts at frame 1.
#pragma once

#include <vector>

#include "penumbra/error.h"
#include "penumbra/frame_plan.h"
#include "penumbra/settings.h"
#include "progressive/distributor.h"

namespace penumbra::progressive {

class FrameRenderer {
 public:
  virtual ~FrameRenderer() = default;
  // Draws and accumulates one intermediate frame. Frame 1 restarts the accumulation.
  virtual Status renderFrame(const FramePlan& plan) = 0;
};

class Controller {
 public:
  explicit Controller(const ProgressiveSettings& settings = {}) : settings_(settings) {}

  // Each of these restarts at frame 1 when it changes anything.
  void setSettings(const ProgressiveSettings& settings);
  void setLights(const std::vector<LightInfo>& lights);
  // A black environment: direct light starts at frame 2 instead of floor(m f_d).
  void setDarkEnvironment(bool dark);
  // The camera or the scene changed: restart (the plan itself stays the same).
  void invalidate() { next_ = 1; }

  // Renders the next frame unless converged. Returns the frame rendered (0 if converged).
  Result<int> step(FrameRenderer& renderer);

  int framesDone() const { return next_ - 1; }
  int totalFrames() const { return settings_.frames; }
  bool converged() const { return next_ > settings_.frames; }
  const std::vector<FramePlan>& plan();
  const ProgressiveSettings& settings() const { return settings_; }

 private:
  ProgressiveSettings settings_;
  std::vector<LightInfo> lights_;
  std::vector<FramePlan> plan_;
  bool planValid_ = false;
  bool darkEnvironment_ = false;
  int next_ = 1;
};

}  // namespace penumbra::progressive
