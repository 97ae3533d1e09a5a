// PointShadowPass: cube shadow maps for point lights. A point light has no size, so its
// visibility is the same every frame: each map is rendered once (six 90-degree faces) the
// first time a frame needs it and kept until the scene changes. Up to kMaxPointShadows maps;
// the lighting shader samples them as samplerCubeShadow (chunks/shadows.glsl), and every slot
// always holds a cube texture (a 1-pixel one until used), since WebGL refuses a draw whose
// sampler units disagree in type.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "gl/program.h"
#include "gl/texture.h"
#include "gpu/gpu_scene.h"
#include "passes/limits.h"
#include "passes/shadow_pass.h"

namespace penumbra::passes {

// What the shader needs to compare against map k: the light's position, the projection's
// near and far planes, and the normal-offset bias (constant, per unit of distance).
struct PointShadowView {
  glm::vec4 position{0.0f};  // xyz
  glm::vec4 params{0.0f};    // x near, y far, z constant offset, w offset per unit distance
};

class PointShadowPass {
 public:
  static Result<PointShadowPass> create(gl::ShaderLibrary& library, int mapSize);
  // The view of map `index` for a light at `position`, rendering the map first unless it
  // already holds this position for the current scene.
  Result<PointShadowView> ensure(int index, const GpuScene& scene, const glm::vec3& position);
  // The scene changed: every map is stale.
  void invalidate();
  // Binds the maps to the program's uPointShadow0, uPointShadow1, ...
  void bind(const gl::Program& program) const;

 private:
  ShadowCasterPrograms programs_;
  int size_ = 0;
  std::array<gl::TextureCube, kMaxPointShadows> maps_;
  std::array<bool, kMaxPointShadows> valid_{};
  std::array<PointShadowView, kMaxPointShadows> views_{};
  gl::Framebuffer framebuffer_;
};

}  // namespace penumbra::passes
