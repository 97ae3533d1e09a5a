// ShadowPass: renders one depth-only shadow map per area-light sample, from a point on the
// light's true surface, with a frustum fitted to the scene bounds inside the light's emitting
// hemisphere (at most 150 degrees wide; receivers outside it count as lit) and slope-scaled
// depth bias. Up to kMaxShadowMaps maps are live at once (one lighting batch). MASK surfaces
// cast cut-out shadows and BLEND surfaces block with probability alpha (stochastic coverage,
// chunks/coverage.glsl: index `coverageFrame`, a `coverageStream` per map of the frame).
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "gl/program.h"
#include "gpu/gpu_scene.h"
#include "passes/limits.h"

namespace penumbra::passes {

struct ShadowView {
  glm::mat4 matrix{1.0f};  // world -> shadow texture space [0, 1]^3
  glm::vec4 params{0.0f};  // see chunks/shadows.glsl
};

// The scene's bounding radius, the length every shadow frustum, near plane and bias is a
// fraction of (no floor in scene units, so a scene modelled in millimetres or kilometres
// gets the same maps); 1 when there are no bounds or they are a single point.
float shadowSceneRadius(const Bounds& sceneBounds);
// The near plane of a perspective shadow map (area-light samples, point-light cube faces).
inline float shadowNearDistance(float sceneRadius) {
  return 1e-3f * sceneRadius;
}

// The light-space frustum for a sample at `origin` emitting along `direction`.
ShadowView fitShadowView(const glm::vec3& origin, const glm::vec3& direction,
                         const glm::vec3& upHint, const Bounds& sceneBounds, int mapSize);
// An orthographic view for light travelling along `direction` (a directional light), fitted
// to the scene's bounding sphere.
ShadowView fitDirectionalShadowView(const glm::vec3& direction, const Bounds& sceneBounds,
                                    int mapSize);

// The two programs that draw shadow casters: opaque surfaces (positions only), and MASK and
// BLEND ones (the material's alpha).
struct ShadowCasterPrograms {
  gl::Program* opaque = nullptr;
  gl::Program* alpha = nullptr;
};
Result<ShadowCasterPrograms> shadowCasterPrograms(gl::ShaderLibrary& library);

// Draws every shadow caster of the scene into the bound depth target with the given view;
// `standIns`: each primitive's capture stand-in (GpuPrimitive::captureIndexCount), for maps
// that only light the probe captures, which draw those too.
void drawShadowCasters(const ShadowCasterPrograms& programs, const GpuScene& scene,
                       const glm::mat4& viewProj, int coverageFrame, int coverageStream,
                       bool standIns = false);

class ShadowPass {
 public:
  // `captureStandIns`: maps for the probe captures only, drawn with the primitives' capture
  // stand-ins like the captures themselves.
  static Result<ShadowPass> create(gl::ShaderLibrary& library, int mapSize,
                                   bool captureStandIns = false);
  // Renders map `slot` for a light sample; returns its view for the lighting pass.
  ShadowView render(int slot, const GpuScene& scene, const glm::vec3& origin,
                    const glm::vec3& direction, const glm::vec3& upHint, int coverageFrame,
                    int coverageStream);
  // Renders map `slot` for a view fitted by the caller (fitDirectionalShadowView).
  ShadowView render(int slot, const GpuScene& scene, const ShadowView& view, int coverageFrame,
                    int coverageStream);
  // Renders map `slot` for one sample of a light: an area light's from `origin` (the sample's
  // point on its surface), a directional light's along `direction` (its jittered direction of
  // travel) over the scene's bounds, a spot light's from its position.
  ShadowView renderLight(int slot, const GpuScene& scene, const Light& light,
                         const glm::vec3& origin, const glm::vec3& direction, int coverageFrame,
                         int coverageStream);
  int size() const { return size_; }
  // Binds the maps (one texture array, a layer per slot) to the program's uShadowMaps.
  void bind(const gl::Program& program) const;
  int mapSize() const { return size_; }
  int64_t memoryBytes() const { return maps_.bytes(); }

 private:
  ShadowCasterPrograms programs_;
  int size_ = 0;
  bool captureStandIns_ = false;
  gl::Texture2DArray maps_;
  std::array<gl::Framebuffer, kMaxShadowMaps> framebuffers_;
};

}  // namespace penumbra::passes
