// AccumulatePass: the running mean mean_n = mean_{n-1} + (x_n - mean_{n-1}) / n of the
// intermediate frames, ping-ponging between the two accumulation targets; non-finite samples
// are dropped (accumulate.frag).
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

 private:
  explicit AccumulatePass(FullscreenPass pass) : pass_(std::move(pass)) {}
  FullscreenPass pass_;
};

}  // namespace penumbra::passes
