// FullscreenPass: one fragment shader over the whole viewport (accumulation, tone mapping,
// background). The caller sets uniforms on program() between begin() and draw().
#pragma once

#include "gl/objects.h"
#include "gl/program.h"

namespace penumbra::passes {

class FullscreenPass {
 public:
  // farPlane: draw at depth 1 (with begin(true), only where no geometry was drawn).
  static Result<FullscreenPass> create(gl::ShaderLibrary& library, const char* fragmentFile,
                                       bool farPlane = false, const gl::Defines& defines = {});
  // Uses the program and sets the pipeline state (no depth test unless `depthTest`).
  const gl::Program& begin(bool depthTest = false) const;
  void draw() const;

 private:
  gl::Program* program_ = nullptr;
  gl::VertexArray vao_;  // attribute-less: the vertex shader derives positions from gl_VertexID
};

}  // namespace penumbra::passes
