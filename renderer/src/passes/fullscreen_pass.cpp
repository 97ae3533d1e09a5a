#include "passes/fullscreen_pass.h"

namespace penumbra::passes {

Result<FullscreenPass> FullscreenPass::create(gl::ShaderLibrary& library, const char* fragmentFile,
                                              bool farPlane, const gl::Defines& defines) {
  gl::Defines all = defines;
  all.emplace_back("PN_FAR_PLANE", farPlane ? "1" : "0");
  auto program = library.program("fullscreen.vert", fragmentFile, all);
  if (!program) return program.error();
  FullscreenPass pass;
  pass.program_ = *program;
  pass.vao_ = gl::VertexArray::create();
  return pass;
}

const gl::Program& FullscreenPass::begin(bool depthTest) const {
  gl::apply({.depthTest = depthTest ? gl::DepthTest::LessEqual : gl::DepthTest::Off,
             .depthWrite = false,
             .blend = gl::Blend::None,
             .cull = gl::Cull::None});
  program_->use();
  return *program_;
}

void FullscreenPass::draw() const {
  vao_.draw(gl::Primitive::Triangles, 3);
}

}  // namespace penumbra::passes
