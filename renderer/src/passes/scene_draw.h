// Draws items of a GpuScene with one program: per-item cull mode (double-sided materials),
// winding (mirrored transforms), transform and, with `material`, the material's uniforms and
// textures. Shared by the prepass and the lighting pass.
#pragma once

#include <vector>

#include "gl/objects.h"
#include "gl/program.h"
#include "gpu/gpu_scene.h"

namespace penumbra::passes {

void drawItem(const gl::Program& program, const GpuScene& scene, const DrawItem& item,
              bool material, gl::PipelineState state);
void drawItems(const gl::Program& program, const GpuScene& scene,
               const std::vector<DrawItem>& items, bool material, gl::PipelineState state);

// Both faces of every item, with uSingleSided telling the shader whether a back face is the
// inside of a closed surface (a probe capture's test for probes buried in geometry), each
// drawn `instances` times (a capture's cube faces), with the primitive's capture stand-in
// (GpuPrimitive::captureIndexCount; scene/mesh_lod.h).
void drawItemBothSides(const gl::Program& program, const GpuScene& scene, const DrawItem& item,
                       gl::PipelineState state, int instances = 1);
void drawItemsBothSides(const gl::Program& program, const GpuScene& scene,
                        const std::vector<DrawItem>& items, gl::PipelineState state,
                        int instances = 1);

}  // namespace penumbra::passes
