// PendingFrame, one part of Renderer::Impl (render/renderer_impl.h): the frame being drawn, as
// render/frame_build.cpp built it from the frame planner's steps.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "passes/camera_math.h"
#include "passes/lighting_pass.h"
#include "penumbra/error.h"
#include "penumbra/frame_plan.h"

namespace penumbra {

// An intermediate frame as a list of units of GL work, run in order. Unsplit (step()) they
// run in one go. Split into `tiles` horizontal bands (stepPart()), every pass over the image
// (prepass, lighting batches, accumulation) runs once per band under a scissor and each
// shadow map is a unit of its own; each unit is one part. Every pixel sees the same draws
// with the same inputs either way, so the image is the same: lighting reads the prepass
// (complete before any lighting unit) and the previous mean (accumulation writes the other
// target and swaps only after its last band), and a batch's shadow maps are drawn before its
// bands and only overwritten after them.
struct PendingFrame {
  FramePlan plan;
  CameraMatrices cm;
  int tiles = 1;
  // The part of the frame target drawn: the whole of it, or a preview's reduced part
  // (ProgressiveSettings::previewScale).
  bool preview = false;
  bool fused = false;  // the lighting pass accumulates (LightingBatch::accumulateFrame)
  int drawWidth = 0, drawHeight = 0;
  std::vector<passes::LightingBatch> batches;
  std::vector<std::function<Status()>> units;
  size_t next = 0;
};

}  // namespace penumbra
