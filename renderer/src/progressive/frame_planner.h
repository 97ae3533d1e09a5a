// The frame planner: turns frame n of the sample plan, the scene's facts and the per-view caches'
// states into a typed list of steps of GPU work (prepass bands, occlusion rays, shadow maps,
// lighting bands of each batch, the transmission copy and compose, probe captures). GL-free, like
// the Controller: the renderer's executor (render/frame_build.cpp) maps each step to a pass, and
// the split-frame invariants (every pixel sees the same draws in the same order whether a frame
// runs in one go or band by band) are plain unit tests (tests/unit/frame_planner_test.cpp).
// Model: Filament's frame graph, without resources: Penumbra's targets are fixed.
#pragma once

#include <vector>

#include "penumbra/frame_plan.h"

namespace penumbra::progressive {

// What the planner needs to know of a light (the renderer's Light, reduced).
struct PlannerLight {
  bool area = false;   // rect or disk: shadow-mapped per sample, cacheable
  bool point = false;  // a point light: a cube map of its own
  bool finite = true;  // intensity and colour are finite numbers
};

// The scene and settings as the planner sees them.
struct FrameScene {
  bool hasScene = false;
  bool blended = false;       // BLEND surfaces: coverage changes every frame
  bool transmissive = false;  // transmissive surfaces: copy, then compose
  std::vector<PlannerLight> lights;
  bool skyShadows = false;  // the setting, a scene, a sampled sky and a lit environment
  bool probes = false;      // the probe volume is on and made
  // Some surface faces another (scene/self_visibility.h), or a transmissive one needs the
  // prepass's depth; without, the prepass and the occlusion rays are skipped (the rays would
  // find nothing).
  bool seesItself = true;
  int probeCount = 0;
  int probeCaptures = 0;  // captures so far
  double probeMeanCaptures = 0.0;
  int probesPerFrame = 2;
  int frames = 0;        // m; 0 (auto) sizes the light cache as a view of 128 frames
  bool preview = false;  // frame 1 as the moving view's reduced stand-in
  int bands = 1;         // horizontal bands the image passes run in
};

// The renderer's switches for A/B runs (RendererOptions) and the GPU layer's limits.
struct FrameLimits {
  bool lightCache = true;
  bool probeCache = true;
  bool fusedAccumulation = true;
  int shadowMaps = 4;      // per lighting batch
  int punctualLights = 8;  // per frame, the sky's direction included
  int pointShadows = 2;    // cube maps
  int cachedLights = 4;    // area lights the per-view cache holds
};

// The per-view caches' counters. Each is owned here and advanced by planFrame() for the frame it
// plans; frame 1 resets them (a new view).
struct CacheState {
  bool prepassValid = false;        // set by the executor once a prepass's last band is drawn
  int lightCacheWritten = 0;        // frames added to the area lights' per-view cache
  int probeCacheFrame = -1;         // the frame the probe volume's per-view cache was made at
};

enum class StepKind {
  Prepass,
  Occlusion,
  ShadowMap,
  PointShadow,
  Lighting,
  CopyBehind,
  Compose,
  ProbeCapture
};

struct FrameStep {
  StepKind kind = StepKind::Lighting;
  int batch = 0;  // ShadowMap, Lighting: the lighting batch
  int band = 0;   // Prepass, Lighting, Compose: the band (of FrameScene::bands)
  // ShadowMap: the area sample's index in its batch, or for a punctual light -1 - j (j its index
  // in FrameSchedule::punctual); PointShadow: j; ProbeCapture: the capture's index this frame.
  int index = 0;
  int stream = 0;           // ShadowMap: the coverage stream of its BLEND decisions (1, 2, ...)
  bool accumulate = false;  // Lighting, Compose: the band also adds the frame to the mean
};

// A punctual light's sample in the first batch, or the sky's direction (sample -1).
struct PlannedPunctual {
  int sample = -1;       // index into FramePlan::lights; -1: the sky
  int pointShadow = -1;  // its cube map
  int shadowSlot = -1;   // its shadow map in the first batch (after the batch's area samples)
};

struct FrameSchedule {
  bool drawPrepass = false;
  bool occlusion = false;
  bool readProbeCache = false;
  bool writeProbeCache = false;
  // The cache was made in an earlier frame of this view, so the occlusion rays, traced before
  // this frame's lighting, may read it too.
  bool occlusionReadsProbeCache = false;
  bool probeLookups = false;
  std::vector<int> cachedLights;  // scene light indices in the per-view cache (all area lights)
  bool writeLightCache = false;
  bool readLightCache = false;
  bool clearLightCache = false;
  float lightCacheWeight = 1.0f;
  bool fused = false;  // one batch that adds its sample to the mean as it draws
  // Area samples per batch: indices into FramePlan::lights, sorted by light (the shader shades a
  // light once for its samples).
  std::vector<std::vector<int>> batches;
  std::vector<PlannedPunctual> punctual;
  int probeCaptures = 0;
  std::vector<FrameStep> steps;  // in order
};

// Plans `plan` for `scene`, advancing `caches` (frame 1 starts them afresh).
FrameSchedule planFrame(const FramePlan& plan, const FrameScene& scene, const FrameLimits& limits,
                        CacheState& caches);

}  // namespace penumbra::progressive
