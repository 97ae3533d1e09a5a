// The sample distributor (Otto et al. 2020, Algorithm 1): decides what each of the m
// intermediate frames evaluates. The environment term is evaluated in every frame (one
// occlusion sample each from frame 2, when the prepass exists); direct-light samples start at
// frame max(2, floor(m * f_d)) and run to frame m; light i gets n_i samples of weight m / n_i,
// so every light carries its full energy at frame m. All lights' samples are merged in
// centre-outward rank order and spread with one Algorithm-1 pass, so the number of shadow-map
// passes per frame differs by at most one between the frames of the direct range.
#pragma once

#include <vector>

#include "penumbra/frame_plan.h"
#include "penumbra/settings.h"
#include "progressive/sequences.h"

namespace penumbra::progressive {

struct LightInfo {
  LightShape shape = LightShape::Rect;
  float aspect = 1.0f;  // rect width / height
  // Part of the environment (its sun): samples from frame 1 on, centre first, so frame 1, the
  // frame shown while navigating, is not missing the light the cube map gave up to it.
  bool fromFrameOne = false;
};

// Samples per light when ProgressiveSettings::lightSamples is 0.
int automaticLightSamples(int frames, float directDelay, int lightCount);
// First frame (1-based) that carries direct-light samples. The delay keeps navigation under
// environment light free of flicker; with a dark environment there is nothing to show before
// direct light, so it starts at frame 2.
int directStartFrame(int frames, float directDelay, bool darkEnvironment = false);

// The whole plan: element k is frame k + 1.
std::vector<FramePlan> distributeSamples(const ProgressiveSettings& settings,
                                         const std::vector<LightInfo>& lights,
                                         bool darkEnvironment = false);

}  // namespace penumbra::progressive
