// OcclusionPass: this frame's diffuse occlusion rays (Otto et al. 2020, section 3.2), traced at
// a quarter of the pixels. Each 2x2 block of the image traces the ray of one of its pixels, a
// different one each frame (four frames cover them all), from the prepass's position and
// normal; the lighting pass uses the block's ray wherever the traced pixel lies on its own
// surface. The march was the largest part of a later frame's lighting pass; on a software
// rasterizer this pass costs about 60 % of it, not a quarter: alone, the march's dependent
// fetches cannot overlap other work (README, Performance).
#pragma once

#include <glm/glm.hpp>

#include "gl/program.h"
#include "passes/fullscreen_pass.h"
#include "passes/targets.h"

namespace penumbra::passes {

struct OcclusionInputs {
  RenderTargets* targets = nullptr;  // reads the prepass and the mean, writes targets->occlusion
  glm::mat4 view{1.0f};              // the prepass's (unjittered) camera
  glm::mat4 projection{1.0f};
  glm::vec2 sequence{0.0f};  // the frame's low-discrepancy point
  int frame = 2;             // picks the pixel of each block
  int block = 2;             // 2: a ray per 2x2 block; 1: per pixel (the A/B reference)
  float occlusionDistance = 1.0f;
  bool indirect = true;  // screen-space indirect light: the hit's radiance
  float indirectClamp = 0.0f;
};

class OcclusionPass {
 public:
  static Result<OcclusionPass> create(gl::ShaderLibrary& library);
  Status trace(const OcclusionInputs& in) const;
  // Which pixel of each 2x2 block traces in frame n (cycles through the four).
  static glm::ivec2 blockOffset(int frame);

 private:
  explicit OcclusionPass(FullscreenPass pass) : pass_(std::move(pass)) {}
  FullscreenPass pass_;
};

}  // namespace penumbra::passes
