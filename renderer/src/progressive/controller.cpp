#include "progressive/controller.h"

#include <algorithm>
#include <cmath>

namespace penumbra::progressive {

void Controller::setSettings(const ProgressiveSettings& settings) {
  if (settings == settings_) return;
  settings_ = settings;
  planValid_ = false;
  restart();
}

void Controller::setLights(const std::vector<LightInfo>& lights) {
  bool same = lights.size() == lights_.size();
  for (size_t i = 0; same && i < lights.size(); ++i) {
    same = lights[i].shape == lights_[i].shape && lights[i].aspect == lights_[i].aspect &&
           lights[i].fromFrameOne == lights_[i].fromFrameOne;
  }
  if (same) return;
  lights_ = lights;
  planValid_ = false;
  restart();
}

void Controller::setFirstLight(bool firstLight) {
  if (firstLight == firstLight_) return;
  firstLight_ = firstLight;
  planValid_ = false;
  restart();
}

const std::vector<FramePlan>& Controller::plan() {
  if (!planValid_) {
    plan_ = distributeSamples(settings_, lights_, firstLight_);
    planValid_ = true;
  }
  return plan_;
}

Result<int> Controller::step(FrameRenderer& renderer) {
  if (converged()) return 0;
  if (!inFrame_) {
    const FramePlan& frame = plan()[static_cast<size_t>(next_ - 1)];
    PN_TRY(renderer.renderFrame(frame));
    const int done = next_;
    PN_TRY(finishFrame(renderer));
    return done;
  }
  for (;;) {
    auto part = stepPart(renderer);
    if (!part) return part.error();
    if (part->done) return part->frame;
  }
}

Result<PartStep> Controller::stepPart(FrameRenderer& renderer) {
  if (converged()) return PartStep{};
  const FramePlan& frame = plan()[static_cast<size_t>(next_ - 1)];
  const bool begin = !inFrame_;
  // A failed part drops the frame: the next call begins it again.
  inFrame_ = false;
  auto done = renderer.renderFramePart(frame, begin);
  if (!done) return done.error();
  if (!*done) {
    inFrame_ = true;
    return PartStep{.frame = next_, .done = false};
  }
  const int complete = next_;
  PN_TRY(finishFrame(renderer));
  return PartStep{.frame = complete, .done = true};
}

Status Controller::finishFrame(FrameRenderer& renderer) {
  const FramePlan& frame = plan()[static_cast<size_t>(next_ - 1)];
  ++next_;
  if (!automatic() || !frame.checkpoint || stopped_) return {};
  auto tiles = renderer.measureTiles(frame.frame);
  if (!tiles) return tiles.error();
  if (tiles->rms.empty()) return {};
  // The change since the kept checkpoint, as the standard error of the image shown now.
  const auto scale = static_cast<float>(changeScale(frame.frame, tiles->against));
  for (float& v : tiles->rms) v *= scale;
  for (float& v : tiles->max) v *= scale;
  const double threshold = settings_.convergenceThreshold;
  // What is left of each tile's error to change before the cap (the oracle's measure: the image
  // against the cap's, which shares the first N frames), sqrt(1 - N / cap) of it for noise; as
  // the 8-bit image shows it (displayedError).
  const double rest =
      std::sqrt(std::max(0.0, 1.0 - frame.frame / static_cast<double>(planFrames(settings_))));
  std::vector<float> errors(tiles->rms.size());
  for (size_t i = 0; i < errors.size(); ++i) errors[i] = displayedError(tiles->rms[i] * rest);
  // The skipped tiles' changes are zero: their frozen ones stand in (TileSkip).
  estimate_ = summarizeTiles(skip_.effective(errors), threshold, frame.frame);
  // How fast the two measures fall, for the view's expected end.
  errorTrend_.push_back({frame.frame, withoutRounding(estimate_.error)});
  tileTrend_.push_back({frame.frame, withoutRounding(estimate_.tileError)});
  estimate_.decay = decayRate(errorTrend_);
  estimate_.tileDecay = decayRate(tileTrend_);
  stopped_ = estimate_.converged;
  if (!stopped_ && settings_.skipConvergedTiles &&
      skip_.update(*tiles, threshold, frame.frame, errors)) {
    PN_TRY(renderer.skipTiles(skip_.mask()));
  }
  estimate_.skippedTiles =
      static_cast<double>(skip_.skipped()) / static_cast<double>(tiles->rms.size());
  return {};
}

int Controller::expectedFrames() const {
  if (!automatic()) return settings_.frames;
  if (stopped_) return framesDone();
  return progressive::expectedFrames(estimate_, settings_.convergenceThreshold,
                                     planFrames(settings_));
}

}  // namespace penumbra::progressive
