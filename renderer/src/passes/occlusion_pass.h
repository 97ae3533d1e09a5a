// OcclusionPass: this frame's diffuse occlusion rays (Otto et al. 2020, section 3.2), traced at
// a quarter of the pixels. Each 2x2 block of the image traces the ray of one of its pixels, a
// different one each frame (four frames cover them all), from the prepass's position and
// normal; the lighting pass uses the block's ray wherever the traced pixel lies on its own
// surface. The march was the largest part of a later frame's lighting pass; on a software
// rasterizer this pass costs about 60 % of it, not a quarter: alone, the march's dependent
// fetches cannot overlap other work (README, Performance).
// A blocked ray stores its hit's radiance minus the unoccluded estimate's toward it (the probe
// volume's radiance maps, else the environment's): the lighting pass adds that, a control
// variate, to the unoccluded irradiance (occlusion_trace.frag). Once the volume's per-view
// cache exists, the probes' radiance comes from one probe drawn by the cache's weights: the
// same mean, at about half the lookup's cost on a software rasterizer.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <memory>

#include "gl/program.h"
#include "passes/fullscreen_pass.h"
#include "passes/targets.h"

namespace penumbra {
class GpuEnvironment;
}

namespace penumbra::passes {

class ProbeVolume;

struct OcclusionInputs {
  RenderTargets* targets = nullptr;  // reads the prepass and the mean, writes targets->occlusion
  glm::mat4 view{1.0f};              // the prepass's (unjittered) camera
  glm::mat4 projection{1.0f};
  glm::vec4 viewOrigin{0.0f, 0.0f, 0.0f, 1.0f};  // CameraMatrices::viewOrigin
  glm::vec2 sequence{0.0f};                      // the frame's low-discrepancy point
  int frame = 2;                                 // picks the pixel of each block
  float filter = 0.0f;  // the neighbouring blocks' weight (FramePlan::rayFilter); 0: none
  int block = 2;  // 2: a ray per 2x2 block; 1: per pixel (the A/B reference)
  float occlusionDistance = 1.0f;
  bool indirect = true;  // screen-space indirect light: the hit's radiance
  float indirectClamp = 0.0f;
  // The unoccluded estimate a hit corrects: the environment (required), turned and scaled as
  // the lighting pass's, and the probe volume where the lighting pass looks it up (else null).
  const GpuEnvironment* environment = nullptr;
  float environmentIntensity = 1.0f;
  glm::mat3 environmentRotation{1.0f};
  const ProbeVolume* probes = nullptr;
  // targets->probeCache holds this view's probe lookups from an earlier frame: the control
  // variate takes the probes' weights from it instead of testing their visibility again.
  bool probeCache = false;
};

class OcclusionPass {
 public:
  static Result<OcclusionPass> create(gl::ShaderLibrary& library);
  Status trace(const OcclusionInputs& in);
  // Which pixel of each 2x2 block traces in frame n (cycles through the four).
  static glm::ivec2 blockOffset(int frame);

 private:
  OcclusionPass(gl::ShaderLibrary& library, FullscreenPass pass, FullscreenPass filter)
      : library_(&library), pass_(std::move(pass)), filter_(std::move(filter)) {}
  // The early frames' edge-aware average of the rays (glsl/occlusion_filter.frag).
  void filter(const OcclusionInputs& in);
  gl::ShaderLibrary* library_;
  FullscreenPass pass_;    // without the probe volume
  FullscreenPass filter_;  // occlusion_filter.frag
  // With it, without and with the per-view cache's weights: built when first needed.
  std::array<std::unique_ptr<FullscreenPass>, 2> probesPass_;
};

}  // namespace penumbra::passes
