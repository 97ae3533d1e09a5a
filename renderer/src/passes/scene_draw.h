// Draws items of a GpuScene with one program: per-item cull mode (double-sided materials),
// winding (mirrored transforms), transform and, with `material`, the material's uniforms and
// textures. Shared by the prepass and the lighting pass.
#pragma once

#include <vector>

#include "gl/objects.h"
#include "gl/program.h"
#include "gpu/gpu_scene.h"

namespace penumbra::passes {

void drawItems(const gl::Program& program, const GpuScene& scene,
               const std::vector<DrawItem>& items, bool material, gl::PipelineState state);

}  // namespace penumbra::passes
