// FramePlan: what one intermediate frame evaluates, as decided by the sample distributor and
// handed by the progressive controller to the renderer. Plain data: the scheduler and the
// renderer share nothing else.
#pragma once

#include <vector>

#include <glm/vec2.hpp>

namespace penumbra {

struct LightSample {
  int light = 0;          // index into Scene::lights
  glm::vec2 point{0.5f};  // position on the light's surface in [0,1]^2 (centre = 0.5, 0.5)
  float weight = 1.0f;    // m / n_i: the light carries its full energy at frame m
  bool shadowed = true;   // render a shadow map from this point (area lights)
};

struct FramePlan {
  int frame = 1;               // 1-based index of this intermediate frame
  int totalFrames = 1;         // m
  glm::vec2 jitter{0.0f};      // sub-pixel offset of the projection, in pixels, in [-0.5, 0.5]
  bool occlusion = false;      // evaluate progressive occlusion (needs the prepass)
  bool renderPrepass = false;  // (re)render the depth and normal prepass before this frame
  glm::vec2 sequence{0.0f};    // this frame's low-discrepancy point for occlusion sampling
  // The weight of the neighbouring blocks' diffuse rays against the pixel's own (0: its own
  // alone): 1 in frame 2, fading to 0 by ProgressiveSettings::rayFilterFrames.
  float rayFilter = 0.0f;
  glm::vec2 skyPoint{0.0f};    // this frame's point for choosing its sky-shadow direction
  // The frame ends a block of the plan (progressive/distributor.h): every light carries its
  // full energy in the mean, which an automatic view measures for convergence here.
  bool checkpoint = false;
  std::vector<LightSample> lights;
};

}  // namespace penumbra
