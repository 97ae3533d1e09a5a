#include "passes/accumulate_pass.h"

#include <cstddef>

namespace penumbra::passes {

Result<AccumulatePass> AccumulatePass::create(gl::ShaderLibrary& library) {
  auto pass = FullscreenPass::create(library, "accumulate.frag");
  if (!pass) return pass.error();
  auto upsample = FullscreenPass::create(library, "upsample.frag");
  if (!upsample) return upsample.error();
  return AccumulatePass(std::move(*pass), std::move(*upsample));
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

}  // namespace penumbra::passes
