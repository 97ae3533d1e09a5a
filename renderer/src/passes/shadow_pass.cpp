#include "passes/shadow_pass.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/light_kinds.h"

namespace penumbra::passes {
namespace {

// Clip space [-1, 1]^3 to shadow-texture space [0, 1]^3.
glm::mat4 clipToTexture() {
  return glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) *
         glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
}

// The view for the shader: world -> texture space, and the normal-offset bias (a constant part
// from the scene's size, and 1.5 texels per unit of the projection's w).
ShadowView shadowView(const glm::mat4& proj, const glm::mat4& view, float sceneRadius,
                      float texelPerW) {
  ShadowView sv;
  sv.matrix = clipToTexture() * proj * view;
  sv.params = glm::vec4(2e-4f * sceneRadius, 1.5f * texelPerW, 0.0f, 0.0f);
  return sv;
}

}  // namespace

float shadowSceneRadius(const Bounds& bounds) {
  const float r = bounds.valid() ? bounds.radius() : 0.0f;
  return r > 0.0f && std::isfinite(r) ? r : 1.0f;
}

ShadowView fitShadowView(const glm::vec3& origin, const glm::vec3& direction,
                         const glm::vec3& upHint, const Bounds& bounds, int mapSize) {
  glm::vec3 up = upHint;
  if (std::abs(glm::dot(glm::normalize(up), direction)) > 0.99f) {
    up = std::abs(direction.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  }
  const glm::mat4 view = glm::lookAt(origin, origin + direction, up);
  const float radius = shadowSceneRadius(bounds);
  const float nearDist = shadowNearDistance(radius);
  const float maxTan = std::tan(glm::radians(75.0f));
  float tanHalf = 0.05f, farDist = nearDist;
  if (bounds.valid()) {
    for (int c = 0; c < 8; ++c) {
      glm::vec3 corner((c & 1) ? bounds.max.x : bounds.min.x, (c & 2) ? bounds.max.y : bounds.min.y,
                       (c & 4) ? bounds.max.z : bounds.min.z);
      glm::vec3 v = glm::vec3(view * glm::vec4(corner, 1.0f));
      farDist = std::max(farDist, glm::length(v));
      const float depth = -v.z;
      if (depth <= 1e-6f * radius) {
        tanHalf = maxTan;  // a corner beside or behind the emitting plane: widest frustum
      } else {
        tanHalf = std::max(tanHalf, std::max(std::abs(v.x), std::abs(v.y)) / depth);
      }
    }
  } else {
    farDist = 10.0f * radius;
    tanHalf = maxTan;
  }
  tanHalf = std::min(tanHalf * 1.02f, maxTan);
  farDist = farDist * 1.01f + nearDist;
  const glm::mat4 proj = glm::perspective(2.0f * std::atan(tanHalf), 1.0f, nearDist, farDist);
  // The texel's size grows with distance: its angle is the offset per unit of w.
  return shadowView(proj, view, radius, 2.0f * tanHalf / static_cast<float>(mapSize));
}

Result<ShadowCasterPrograms> shadowCasterPrograms(gl::ShaderLibrary& library) {
  auto program = library.program("shadow.vert", "shadow.frag");
  if (!program) return program.error();
  auto alphaProgram = library.program("mesh.vert", "shadow_alpha.frag");
  if (!alphaProgram) return alphaProgram.error();
  return ShadowCasterPrograms{*program, *alphaProgram};
}

Result<ShadowPass> ShadowPass::create(gl::ShaderLibrary& library, int mapSize,
                                      bool captureStandIns) {
  ShadowPass pass;
  auto programs = shadowCasterPrograms(library);
  if (!programs) return programs.error();
  pass.programs_ = *programs;
  pass.size_ = mapSize;
  pass.captureStandIns_ = captureStandIns;
  auto maps = gl::Texture2DArray::create({.width = mapSize,
                                          .height = mapSize,
                                          .format = gl::PixelFormat::Depth24,
                                          .sampler = {.minFilter = gl::Filter::Linear,
                                                      .magFilter = gl::Filter::Linear,
                                                      .depthCompare = true}},
                                         kMaxShadowMaps);
  if (!maps) return makeError("shadow maps: " + maps.message());
  pass.maps_ = std::move(*maps);
  for (int i = 0; i < kMaxShadowMaps; ++i) {
    gl::Framebuffer fb = gl::Framebuffer::create();
    fb.attachDepth(pass.maps_, i);
    fb.setDrawBuffers(0);
    PN_TRY(fb.checkComplete());
    pass.framebuffers_[static_cast<size_t>(i)] = std::move(fb);
  }
  gl::Framebuffer::bindDefault();
  return pass;
}

ShadowView fitDirectionalShadowView(const glm::vec3& direction, const Bounds& bounds, int mapSize) {
  const glm::vec3 d = glm::normalize(direction);
  const glm::vec3 center = bounds.valid() ? bounds.center() : glm::vec3(0.0f);
  const float radius = shadowSceneRadius(bounds);
  const glm::vec3 up = std::abs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 eye = center - d * (2.0f * radius);
  const glm::mat4 view = glm::lookAt(eye, center, up);
  const glm::mat4 proj = glm::ortho(-radius, radius, -radius, radius, radius * 0.5f, radius * 3.5f);
  // w is 1 in a parallel projection: the offset is the texel size itself.
  return shadowView(proj, view, radius, 2.0f * radius / static_cast<float>(mapSize));
}

ShadowView ShadowPass::render(int slot, const GpuScene& scene, const glm::vec3& origin,
                              const glm::vec3& direction, const glm::vec3& upHint,
                              int coverageFrame, int coverageStream) {
  return render(slot, scene, fitShadowView(origin, direction, upHint, scene.bounds(), size_),
                coverageFrame, coverageStream);
}

ShadowView ShadowPass::renderLight(int slot, const GpuScene& scene, const Light& light,
                                   const glm::vec3& origin, const glm::vec3& direction,
                                   int coverageFrame, int coverageStream) {
  if (lightKind(light.type).shadow == ShadowProjection::Orthographic) {
    return render(slot, scene, fitDirectionalShadowView(direction, scene.bounds(), size_),
                  coverageFrame, coverageStream);
  }
  const glm::vec3 from = light.isArea() ? origin : light.position;
  return render(slot, scene, from, light.direction, light.up, coverageFrame, coverageStream);
}

ShadowView ShadowPass::render(int slot, const GpuScene& scene, const ShadowView& sv,
                              int coverageFrame, int coverageStream) {
  const glm::mat4 bias = clipToTexture();
  const glm::mat4 viewProj = glm::inverse(bias) * sv.matrix;
  framebuffers_[static_cast<size_t>(slot)].bind();
  gl::setViewport(0, 0, size_, size_);
  gl::clearDepth(1.0f);
  drawShadowCasters(programs_, scene, viewProj, coverageFrame, coverageStream, captureStandIns_);
  return sv;
}

void drawShadowCasters(const ShadowCasterPrograms& programs, const GpuScene& scene,
                       const glm::mat4& viewProj, int coverageFrame, int coverageStream,
                       bool standIns) {
  // Both faces cast: open meshes and single-sided walls must still block light.
  gl::apply({.depthTest = gl::DepthTest::Less,
             .depthWrite = true,
             .cull = gl::Cull::None,
             .colorWrite = false,
             .polygonOffsetFactor = 1.5f,
             .polygonOffsetUnits = 2.0f});
  // Opaque surfaces first with the position-only program, then those that need their alpha.
  for (const bool alpha : {false, true}) {
    gl::Program& program = alpha ? *programs.alpha : *programs.opaque;
    bool used = false;
    for (const auto* list : {&scene.opaque(), &scene.blended(), &scene.transmissive()}) {
      for (const DrawItem& item : *list) {
        if (!item.castsShadow || scene.needsAlpha(item) != alpha) continue;
        if (!used) {
          program.use();
          program.set("uViewProj", viewProj);
          program.set("uCoverageFrame", coverageFrame);
          program.set("uCoverageStream", coverageStream);
          used = true;
        }
        scene.bindTransform(program, item);
        if (alpha) scene.bindMaterial(program, item.material);
        const GpuPrimitive& prim = *item.primitive;
        prim.vao.drawInstanced(gl::Primitive::Triangles,
                               standIns ? prim.captureIndexCount : prim.indexCount, item.copies,
                               standIns ? prim.captureByteOffset : 0);
      }
    }
  }
}

void ShadowPass::bind(const gl::Program& program) const {
  program.bind("uShadowMaps", maps_);
}

}  // namespace penumbra::passes
