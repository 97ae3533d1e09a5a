// Prepass: view-space normal and linear view depth of the scene for an unjittered camera,
// read by the occlusion rays (RGBA16F where renderable). BLEND surfaces take part with the
// frame's stochastic coverage (chunks/coverage.glsl), MASK surfaces are cut out.
#pragma once

#include <glm/glm.hpp>

#include "gl/program.h"
#include "gpu/gpu_scene.h"
#include "passes/targets.h"

namespace penumbra::passes {

class Prepass {
 public:
  static Result<Prepass> create(gl::ShaderLibrary& library);
  // Into targets.prepass; `scene` may be null (cleared only).
  void render(RenderTargets& targets, const GpuScene* scene, const glm::mat4& view,
              const glm::mat4& projection, int coverageFrame) const;

 private:
  gl::Program* program_ = nullptr;
};

}  // namespace penumbra::passes
