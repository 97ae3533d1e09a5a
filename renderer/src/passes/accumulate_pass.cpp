#include "passes/accumulate_pass.h"

#include <cstddef>

namespace penumbra::passes {

Result<AccumulatePass> AccumulatePass::create(gl::ShaderLibrary& library) {
  auto pass = FullscreenPass::create(library, "accumulate.frag");
  if (!pass) return pass.error();
  auto upsample = FullscreenPass::create(library, "upsample.frag");
  if (!upsample) return upsample.error();
  auto hold = FullscreenPass::create(library, "first_frame_hold.frag");
  if (!hold) return hold.error();
  return AccumulatePass(std::move(*pass), std::move(*upsample), std::move(*hold));
}

void AccumulatePass::draw(const RenderTargets& targets, int n) const {
  const auto prev = static_cast<std::size_t>(targets.current);
  const auto next = static_cast<std::size_t>(1 - targets.current);
  targets.accumulation[next].framebuffer.bind();
  gl::setViewport(0, 0, targets.width, targets.height);
  const gl::Program& p = pass_.begin();
  p.bind("uPrevious", targets.accumulation[prev].color);
  p.bind("uCurrent", targets.frame.color);
  p.set("uWeight", 1.0f / static_cast<float>(n));
  pass_.draw();
}

void AccumulatePass::upsampleFirst(const RenderTargets& targets, int drawnWidth,
                                   int drawnHeight) const {
  PN_CHECK(drawnWidth >= 1 && drawnWidth <= targets.width && drawnHeight >= 1 &&
               drawnHeight <= targets.height,
           "upsampleFirst: the drawn size lies within the targets");
  targets.accumulation[static_cast<std::size_t>(1 - targets.current)].framebuffer.bind();
  gl::setViewport(0, 0, targets.width, targets.height);
  const gl::Program& p = upsample_.begin();
  p.bind("uCurrent", targets.frame.color);
  p.set("uDrawnSize", glm::vec2(drawnWidth, drawnHeight));
  upsample_.draw();
}

void AccumulatePass::keepFirst(const RenderTargets& targets) const {
  PN_CHECK(static_cast<bool>(targets.firstFrame.color), "keepFirst: ensureFirstFrameHold first");
  targets.accumulation[static_cast<std::size_t>(targets.current)].framebuffer.blitColorTo(
      targets.firstFrame.framebuffer, targets.width, targets.height);
}

void AccumulatePass::drawHeld(const RenderTargets& targets, float hold) const {
  PN_CHECK(static_cast<bool>(targets.held.color), "drawHeld: ensureFirstFrameHold first");
  PN_CHECK(hold > 0.0f && hold < 1.0f, "drawHeld: the hold is in (0, 1)");
  targets.held.framebuffer.bind();
  gl::setViewport(0, 0, targets.width, targets.height);
  const gl::Program& p = hold_.begin();
  p.bind("uMean", targets.accumulation[static_cast<std::size_t>(targets.current)].color);
  p.bind("uFirst", targets.firstFrame.color);
  p.set("uHold", hold);
  hold_.draw();
}

}  // namespace penumbra::passes
