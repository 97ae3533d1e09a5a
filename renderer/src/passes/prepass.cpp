#include "passes/prepass.h"

#include "passes/scene_draw.h"

namespace penumbra::passes {

Result<Prepass> Prepass::create(gl::ShaderLibrary& library) {
  Prepass pass;
  auto program = library.program("mesh.vert", "prepass.frag");
  if (!program) return program.error();
  pass.program_ = *program;
  return pass;
}

void Prepass::render(RenderTargets& targets, const GpuScene* scene, const glm::mat4& view,
                     const glm::mat4& projection, int coverageFrame) const {
  targets.prepass.framebuffer.bind();
  gl::setViewport(0, 0, targets.width, targets.height);
  gl::apply({});
  gl::clearBufferFloat(0, 0, 0, 0, 0);
  gl::clearDepth(1.0f);
  const gl::Program& p = *program_;
  p.use();
  p.set("uViewProj", projection * view);
  p.set("uView", view);
  p.set("uCoverageFrame", coverageFrame);
  p.set("uCoverageStream", 0);
  if (!scene) return;
  drawItems(p, *scene, scene->opaque(), true, {});
  drawItems(p, *scene, scene->blended(), true, {});
}

}  // namespace penumbra::passes
