#include "passes/point_shadow_pass.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "passes/shadow_pass.h"

namespace penumbra::passes {
namespace {

Result<gl::TextureCube> depthCube(int size) {
  return gl::TextureCube::create({.width = size,
                                  .format = gl::PixelFormat::Depth24,
                                  .sampler = {.minFilter = gl::Filter::Linear,
                                              .magFilter = gl::Filter::Linear,
                                              .depthCompare = true}});
}

}  // namespace

Result<PointShadowPass> PointShadowPass::create(gl::ShaderLibrary& library, int mapSize) {
  PointShadowPass pass;
  auto programs = shadowCasterPrograms(library);
  if (!programs) return programs.error();
  pass.programs_ = *programs;
  pass.size_ = mapSize;
  for (auto& map : pass.maps_) {
    auto cube = depthCube(1);
    if (!cube) return makeError("point shadow map: " + cube.message());
    map = std::move(*cube);
  }
  pass.framebuffer_ = gl::Framebuffer::create();
  return pass;
}

void PointShadowPass::invalidate() {
  valid_.fill(false);
}

Result<PointShadowView> PointShadowPass::ensure(int index, const GpuScene& scene,
                                                const glm::vec3& position) {
  PN_CHECK(index >= 0 && index < kMaxPointShadows, "point shadow index out of range");
  const auto k = static_cast<size_t>(index);
  if (valid_[k] && glm::vec3(views_[k].position) == position) return views_[k];
  if (maps_[k].size() != size_) {
    auto cube = depthCube(size_);
    if (!cube) return makeError("point shadow map: " + cube.message());
    maps_[k] = std::move(*cube);
  }
  const Bounds& b = scene.bounds();
  const float radius = shadowSceneRadius(b);
  const float nearDist = shadowNearDistance(radius);
  float farDist = nearDist;
  if (b.valid()) {
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 corner((c & 1) ? b.max.x : b.min.x, (c & 2) ? b.max.y : b.min.y,
                             (c & 4) ? b.max.z : b.min.z);
      farDist = std::max(farDist, glm::length(corner - position));
    }
  }
  farDist = farDist * 1.01f + nearDist;
  const glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, nearDist, farDist);
  // The GL cube-map faces: the direction each looks along and its up vector.
  static const glm::vec3 kAxis[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                     {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  static const glm::vec3 kUp[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                                   {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  framebuffer_.setDrawBuffers(0);
  for (int face = 0; face < 6; ++face) {
    framebuffer_.attachDepth(maps_[k], face);
    if (face == 0) PN_TRY(framebuffer_.checkComplete());
    gl::setViewport(0, 0, size_, size_);
    gl::clearDepth(1.0f);
    const glm::mat4 view = glm::lookAt(position, position + kAxis[face], kUp[face]);
    drawShadowCasters(programs_, scene, proj * view, 0, 1);
  }
  views_[k].position = glm::vec4(position, 1.0f);
  // A texel spans 2 / size in tangent at unit distance; offset by 1.5 of them, as ShadowPass.
  views_[k].params = glm::vec4(nearDist, farDist, 2e-4f * radius, 3.0f / static_cast<float>(size_));
  valid_[k] = true;
  return views_[k];
}

void PointShadowPass::bind(const gl::Program& program) const {
  for (int i = 0; i < kMaxPointShadows; ++i) {
    program.bind("uPointShadow" + std::to_string(i), maps_[static_cast<size_t>(i)]);
  }
}

}  // namespace penumbra::passes
