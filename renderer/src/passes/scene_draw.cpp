#include "passes/scene_draw.h"

namespace penumbra::passes {

void drawItem(const gl::Program& program, const GpuScene& scene, const DrawItem& item,
              bool material, gl::PipelineState state) {
  const Material& m = scene.material(item.material).source;
  state.cull = m.doubleSided ? gl::Cull::None : gl::Cull::Back;
  state.frontFaceClockwise = item.mirrored;
  gl::apply(state);
  scene.bindTransform(program, item);
  if (material) scene.bindMaterial(program, item.material);
  item.primitive->vao.drawInstanced(gl::Primitive::Triangles, item.primitive->indexCount,
                                    item.copies);
}

void drawItems(const gl::Program& program, const GpuScene& scene,
               const std::vector<DrawItem>& items, bool material, gl::PipelineState state) {
  for (const DrawItem& item : items) drawItem(program, scene, item, material, state);
}

void drawItemBothSides(const gl::Program& program, const GpuScene& scene, const DrawItem& item,
                       gl::PipelineState state, int instances) {
  const Material& m = scene.material(item.material).source;
  state.cull = gl::Cull::None;
  state.frontFaceClockwise = item.mirrored;  // gl_FrontFacing must still mean the front
  gl::apply(state);
  program.set("uSingleSided", m.doubleSided ? 0 : 1);
  scene.bindTransform(program, item, instances);
  scene.bindMaterial(program, item.material);
  // Only the probe captures draw this way: with the primitive's capture stand-in.
  item.primitive->vao.drawInstanced(gl::Primitive::Triangles, item.primitive->captureIndexCount,
                                    instances * item.copies, item.primitive->captureByteOffset);
}

void drawItemsBothSides(const gl::Program& program, const GpuScene& scene,
                        const std::vector<DrawItem>& items, gl::PipelineState state,
                        int instances) {
  for (const DrawItem& item : items) drawItemBothSides(program, scene, item, state, instances);
}

}  // namespace penumbra::passes
