// AccumulatePass: the running mean mean_n = mean_{n-1} + (x_n - mean_{n-1}) / n of the
// intermediate frames, ping-ponging between the two accumulation targets; non-finite samples
// are dropped (accumulate.frag). A frame 1 drawn at a reduced size becomes the mean upsampled
// (upsample.frag).
#pragma once

#include "passes/fullscreen_pass.h"
#include "passes/targets.h"

namespace penumbra::passes {

class AccumulatePass {
 public:
  static Result<AccumulatePass> create(gl::ShaderLibrary& library);
  // Adds targets.frame as frame n into the other accumulation target (within the scissor, for
  // a frame drawn in bands). The caller makes it current once the whole image is done: until
  // then the previous mean stays readable.
  void draw(const RenderTargets& targets, int n) const;
  // Frame 1, drawn into the bottom-left drawnWidth x drawnHeight texels of targets.frame,
  // upsampled into the other accumulation target over the whole image (the caller makes it
  // current).
  void upsampleFirst(const RenderTargets& targets, int drawnWidth, int drawnHeight) const;
  // Stochastic transparency's early frames (progressive/first_frame_hold.h): keepFirst copies
  // the mean after frame 1 into targets.firstFrame; drawHeld draws mix(mean, first, hold) into
  // targets.held, the image to display. Both need RenderTargets::ensureFirstFrameHold.
  void keepFirst(const RenderTargets& targets) const;
  void drawHeld(const RenderTargets& targets, float hold) const;

 private:
  AccumulatePass(FullscreenPass pass, FullscreenPass upsample, FullscreenPass hold)
      : pass_(std::move(pass)), upsample_(std::move(upsample)), hold_(std::move(hold)) {}
  FullscreenPass pass_;
  FullscreenPass upsample_;
  FullscreenPass hold_;
};

}  // namespace penumbra::passes
