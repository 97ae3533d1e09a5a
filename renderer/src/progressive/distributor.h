// The sample distributor (Otto et al. 2020, Algorithm 1): decides what each intermediate frame
// evaluates. The environment term is evaluated in every frame (one occlusion sample each from
// frame 2, when the prepass exists); direct-light samples start at frame max(2, floor(m f_d)).
// All lights' samples are merged in centre-outward rank order and spread with one Algorithm-1
// pass, so the number of shadow-map passes per frame differs by at most one between the frames
// of the direct range.
//
// The plan is a sequence of blocks. A fixed m is one block, frames 1..m, with one stratified set
// of light samples. An automatic view (frames 0) is open-ended: blocks end at checkpoints about
// 2^(1/4) apart (autoCheckpoints) up to maxFrames, and each light's samples are the next points
// of one open-ended low-discrepancy sequence (lightSequencePoint), so the samples up to any
// checkpoint are a stratified prefix. Light i's n_i samples of a block of length len weigh
// len / n_i, so at every block end (a checkpoint) each light carries its full energy and the
// running mean is a complete estimate, wherever an automatic view stops.
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

// An automatic view's checkpoints: 2, 4, 6, 8, then each about kCheckpointRatio times the last
// (10, 12, 14, 17, 20, ...), and the cap. Fine enough that a stop lands within 1.19x of the
// frame where the view first measures converged; frame 1 (environment and first light alone)
// ends the first block with frame 2.
inline constexpr double kCheckpointRatio = 1.189207115002721;  // 2^(1/4)
std::vector<int> autoCheckpoints(int cap);

// First frame (1-based) that carries direct-light samples of a block of `frames` frames. The
// delay keeps navigation under environment light free of flicker; where the scene's own lights
// carry it (firstLight) they start at frame 2, after frame 1's first light.
int directStartFrame(int frames, float directDelay, bool firstLight = false);

// The weight of the neighbouring blocks' diffuse rays in frame `frame` (FramePlan::rayFilter):
// 1 in frame 2 (the first with rays), falling linearly to 0 at frame fadeFrames + 1; 0 where
// fadeFrames < 2 (off).
float rayFilterWeight(int frame, int fadeFrames);

// The whole plan, up to planFrames(settings): element k is frame k + 1. firstLight: the
// scene's own lights carry it (Renderer: the environment would give frame 1 less than half of
// the light), so frame 1 evaluates every light from its centre with weight 1, and the rest of
// the first block's samples share what remains of its weight.
std::vector<FramePlan> distributeSamples(const ProgressiveSettings& settings,
                                         const std::vector<LightInfo>& lights,
                                         bool firstLight = false);

}  // namespace penumbra::progressive
