#include "progressive/frame_planner.h"

#include <algorithm>

#include "progressive/light_cache.h"
#include "progressive/probe_grid.h"

namespace penumbra::progressive {
namespace {

// The prepass, the occlusion rays and the per-view caches' decisions.
void planCaches(const FramePlan& plan, const FrameScene& scene, const FrameLimits& limits,
                CacheState& caches, FrameSchedule& s) {
  // BLEND surfaces cover the pixels differently each frame: the occlusion rays must see this
  // frame's coverage, so the prepass is redrawn every frame when there are any.
  const bool coverageChanges = scene.hasScene && scene.blended;
  const bool occlusion = plan.occlusion && scene.seesItself;
  s.drawPrepass = occlusion && (plan.renderPrepass || !caches.prepassValid || coverageChanges);
  s.occlusion = occlusion && (s.drawPrepass || caches.prepassValid);
  // The probe volume's per-view cache, read in between remakes (remakeProbeCache).
  s.readProbeCache = s.occlusion && scene.probes && limits.probeCache;
  const double captured = scene.probes ? scene.probeMeanCaptures : 0.0;
  const int since = caches.probeCacheFrame < 0 ? -1 : plan.frame - caches.probeCacheFrame;
  s.writeProbeCache = s.readProbeCache && remakeProbeCache(since, captured);
  s.occlusionReadsProbeCache = s.readProbeCache && since > 0;
  if (s.writeProbeCache) caches.probeCacheFrame = plan.frame;
  // An empty volume (no capture yet: the first frame after a reset) answers nothing, so frames
  // without occlusion rays skip its per-pixel lookup; later frames keep it, so that the
  // per-view cache's remakes stay on their schedule.
  s.probeLookups = scene.probes && (s.occlusion || scene.probeCaptures > 0);
  // The area lights' per-view cache (light_cache.h): every area light of the scene (up to
  // limits.cachedLights), opaque scenes only (BLEND surfaces cover differently each frame).
  if (limits.lightCache && scene.hasScene && !scene.blended) {
    for (size_t i = 0; i < scene.lights.size(); ++i) {
      if (scene.lights[i].area) s.cachedLights.push_back(static_cast<int>(i));
    }
    if (s.cachedLights.size() > static_cast<size_t>(limits.cachedLights)) s.cachedLights.clear();
  }
  // An automatic view sizes the cache as a view of 128 frames (its stopping point is unknown).
  const int m = scene.frames > 0 ? scene.frames : 128;
  const bool cached = !s.cachedLights.empty();
  s.writeLightCache = cached && writesLightCache(plan.frame, caches.lightCacheWritten, m);
  s.readLightCache = cached && lightCacheReady(caches.lightCacheWritten, m);
  s.clearLightCache = s.writeLightCache && caches.lightCacheWritten == 0;
  if (s.writeLightCache) ++caches.lightCacheWritten;
  s.lightCacheWeight = 1.0f / static_cast<float>(lightCacheFrames(m));
}

// The frame's light samples: area samples into batches of up to limits.shadowMaps (the first
// batch's shadow maps shared with the punctual lights'), punctual ones into the first batch.
void planLights(const FramePlan& plan, const FrameScene& scene, const FrameLimits& limits,
                FrameSchedule& s, std::vector<int>& area) {
  for (size_t k = 0; k < plan.lights.size(); ++k) {
    const int light = plan.lights[k].light;
    if (light < 0 || light >= static_cast<int>(scene.lights.size())) continue;
    const PlannerLight& l = scene.lights[static_cast<size_t>(light)];
    // Frame 1 becomes the mean without the accumulation's guard against non-finite samples:
    // a light that can only give NaN (first light) is left out of it.
    if (plan.frame == 1 && !l.finite) continue;
    if (l.area) {
      area.push_back(static_cast<int>(k));
    } else {
      s.punctual.push_back({.sample = static_cast<int>(k)});
    }
  }
  // Sky shadows: one direction of the sunless environment a frame, from the frames with
  // occlusion on (the diffuse term it corrects is then a per-frame estimate anyway).
  if (plan.occlusion && scene.skyShadows &&
      s.punctual.size() < static_cast<size_t>(limits.punctualLights)) {
    s.punctual.push_back({.sample = -1});
  }
  // Spot and directional samples (first batch only) take shadow maps before area samples; the
  // first point lights take cube maps, rendered once per scene.
  int punctualMaps = 0;
  int pointMaps = 0;
  for (PlannedPunctual& p : s.punctual) {
    if (!scene.hasScene) break;
    const bool point =
        p.sample >= 0 &&
        scene.lights[static_cast<size_t>(plan.lights[static_cast<size_t>(p.sample)].light)].point;
    if (point) {
      if (pointMaps < limits.pointShadows) p.pointShadow = pointMaps++;
    } else if (punctualMaps < limits.shadowMaps) {
      p.shadowSlot = punctualMaps++;
    }
  }
  const size_t batchSize = static_cast<size_t>(limits.shadowMaps);
  const size_t firstBatch = batchSize - static_cast<size_t>(punctualMaps);
  const size_t batches =
      area.size() <= firstBatch ? 1 : 1 + (area.size() - firstBatch + batchSize - 1) / batchSize;
  for (size_t b = 0; b < batches; ++b) {
    const size_t from = b == 0 ? 0 : firstBatch + (b - 1) * batchSize;
    const size_t to = b == 0 ? firstBatch : from + batchSize;
    std::vector<int> samples(
        area.begin() + static_cast<std::ptrdiff_t>(std::min(from, area.size())),
        area.begin() + static_cast<std::ptrdiff_t>(std::min(to, area.size())));
    // Sorted by light: the shader computes a light's unshadowed shading once for its samples.
    std::stable_sort(samples.begin(), samples.end(), [&](int x, int y) {
      return plan.lights[static_cast<size_t>(x)].light < plan.lights[static_cast<size_t>(y)].light;
    });
    s.batches.push_back(std::move(samples));
  }
  // The punctual maps follow the first batch's area samples.
  for (PlannedPunctual& p : s.punctual) {
    if (p.shadowSlot >= 0) p.shadowSlot += static_cast<int>(s.batches.front().size());
  }
}

// The steps, in order: prepass bands, occlusion, then per batch its shadow maps and its bands,
// the transmission copy and compose bands, and the probe captures.
void planSteps(const FramePlan& plan, const FrameScene& scene, FrameSchedule& s) {
  const int k = std::max(1, scene.bands);
  auto& steps = s.steps;
  if (s.drawPrepass) {
    for (int t = 0; t < k; ++t) steps.push_back({.kind = StepKind::Prepass, .band = t});
  }
  if (s.occlusion) steps.push_back({.kind = StepKind::Occlusion});
  int stream = 0;  // each shadow map of the frame decides coverage on its own
  for (size_t b = 0; b < s.batches.size(); ++b) {
    const int batch = static_cast<int>(b);
    for (size_t i = 0; i < s.batches[b].size(); ++i) {
      const LightSample& sample = plan.lights[static_cast<size_t>(s.batches[b][i])];
      if (sample.shadowed && scene.hasScene) {
        steps.push_back({.kind = StepKind::ShadowMap,
                         .batch = batch,
                         .index = static_cast<int>(i),
                         .stream = ++stream});
      }
    }
    if (b == 0) {
      for (size_t j = 0; j < s.punctual.size(); ++j) {
        const PlannedPunctual& p = s.punctual[j];
        if (p.pointShadow >= 0) {
          steps.push_back({.kind = StepKind::PointShadow, .index = static_cast<int>(j)});
        } else if (p.shadowSlot >= 0) {
          steps.push_back({.kind = StepKind::ShadowMap,
                           .batch = 0,
                           .index = -1 - static_cast<int>(j),
                           .stream = ++stream});
        }
      }
    }
    // Without transmissive surfaces the last batch's bands also accumulate; with them the
    // accumulation waits for their compose.
    const bool accumulate = b + 1 == s.batches.size() && !scene.transmissive;
    for (int t = 0; t < k; ++t) {
      steps.push_back(
          {.kind = StepKind::Lighting, .batch = batch, .band = t, .accumulate = accumulate});
    }
  }
  if (scene.transmissive) {
    // Transmissive surfaces look through a copy of the whole frame (a refracted ray may land in
    // another band): the copy after every band's lighting, then each band composes and
    // accumulates.
    steps.push_back({.kind = StepKind::CopyBehind});
    for (int t = 0; t < k; ++t) {
      steps.push_back({.kind = StepKind::Compose, .band = t, .accumulate = true});
    }
  }
  // Probe captures, the frame's last steps, one probe each (a frame dropped part-way keeps the
  // captures it made): every frame but the first, which captures only until the volume has
  // settled (so it still fills while a viewer orbits and frame 1 is all it draws), and never
  // before the first frame after a reset (the first image comes as fast as without the volume).
  if (scene.probes && (plan.frame >= 2 || (scene.probeCaptures > 0 &&
                                           scene.probeMeanCaptures < kProbeSettledCaptures))) {
    s.probeCaptures = probeCapturesThisFrame(scene.probesPerFrame, scene.probeCount,
                                             scene.probeMeanCaptures, plan.frame);
    for (int i = 0; i < s.probeCaptures; ++i) {
      steps.push_back({.kind = StepKind::ProbeCapture, .index = i});
    }
  }
}

}  // namespace

FrameSchedule planFrame(const FramePlan& plan, const FrameScene& scene, const FrameLimits& limits,
                        CacheState& caches) {
  if (plan.frame == 1) caches = {};
  FrameSchedule s;
  planCaches(plan, scene, limits, caches, s);
  std::vector<int> area;
  planLights(plan, scene, limits, s, area);
  // One batch and nothing drawn over it: it adds its sample to the mean as it draws.
  s.fused = limits.fusedAccumulation && s.batches.size() == 1 && !scene.transmissive &&
            plan.frame > 1 && !scene.preview;
  planSteps(plan, scene, s);
  return s;
}

}  // namespace penumbra::progressive
