// Renderer::Impl::beginFrame, the executor of the frame planner (progressive/frame_planner.h):
// frame n's steps become units of GL work (prepass, occlusion rays, shadow maps, lighting
// batches band by band, accumulation, probe captures), run by runPart() one at a time or all at
// once (docs/architecture.md, "In parts"). The decisions are the planner's; here they meet the
// passes.
#include "render/renderer_impl.h"

namespace penumbra {

progressive::FrameScene Renderer::Impl::frameScene(bool preview) const {
  progressive::FrameScene fs;
  fs.hasScene = scene != nullptr;
  fs.blended = scene && !scene->blended().empty();
  fs.transmissive = scene && !scene->transmissive().empty();
  fs.lights.reserve(lights.size());
  for (const Light& l : lights) {
    fs.lights.push_back({.area = l.isArea(),
                         .point = lightKind(l.type).shadow == ShadowProjection::Cube,
                         .finite = std::isfinite(l.intensity) && std::isfinite(l.color.r) &&
                                   std::isfinite(l.color.g) && std::isfinite(l.color.b)});
  }
  // A ground shadow catches the environment's shadows through the sky-shadow samples.
  fs.skyShadows = (settings.progressive.skyShadows || settings.shadowIntensity > 0.0f) && scene &&
                  !sky.empty() && environmentMean * settings.environmentIntensity > 0.0f;
  fs.probes = probesOn();
  // Transmissive surfaces read the prepass's depth (the surface behind them) even when
  // nothing can occlude anything.
  fs.seesItself = seesItself || fs.transmissive;
  if (fs.probes) {
    fs.probeCount = probes->grid().count();
    fs.probeCaptures = probes->captures();
    fs.probeMeanCaptures = probes->meanCaptures();
  }
  fs.probesPerFrame = settings.progressive.probesPerFrame;
  fs.frames = settings.progressive.frames;
  fs.preview = preview;
  fs.bands = pending.tiles;
  return fs;
}

progressive::FrameLimits Renderer::Impl::frameLimits() const {
  return {.lightCache = options.lightCache,
          .probeCache = options.probeCache,
          // The ground multiplies the frame's background (passes/ground_shadow.cpp): the
          // frame then needs its own target, not the running mean.
          .fusedAccumulation = options.fusedAccumulation && settings.shadowIntensity <= 0.0f,
          .shadowMaps = passes::kMaxShadowMaps,
          .punctualLights = passes::kMaxPunctualLights,
          .pointShadows = passes::kMaxPointShadows,
          .cachedLights = passes::kMaxCachedLights};
}

// The lighting batches of the schedule: what each draws (its area samples, the first batch's
// punctual lights and sky direction) and which caches it reads and writes.
void Renderer::Impl::buildBatches(const progressive::FrameSchedule& fs, float occlusionDistance) {
  const FramePlan& plan = pending.plan;
  std::vector<passes::AreaSampleDraw> cachedLights;
  for (int i : fs.cachedLights) {
    cachedLights.push_back({&lights[static_cast<size_t>(i)], i});
  }
  std::vector<passes::PunctualDraw> punctual;
  for (const progressive::PlannedPunctual& p : fs.punctual) {
    passes::PunctualDraw pd;
    if (p.sample >= 0) {
      const LightSample& s = plan.lights[static_cast<size_t>(p.sample)];
      const Light& l = lights[static_cast<size_t>(s.light)];
      pd = {&l, s.weight, render::punctualDirection(l, s.point, settings)};
    } else {
      skySample = render::skyLight(sky.sample(plan.skyPoint), settings);
      pd = {&skySample, 1.0f, skySample.direction};
      pd.skyLoss = true;
    }
    pd.shadowSlot = p.shadowSlot;
    pd.pointShadow = p.pointShadow;
    punctual.push_back(pd);
  }
  pending.batches.reserve(fs.batches.size());
  for (size_t b = 0; b < fs.batches.size(); ++b) {
    pending.batches.push_back(
        passes::LightingBatch{.targets = &*targets,
                              .drawWidth = pending.drawWidth,
                              .drawHeight = pending.drawHeight,
                              .scene = scene.get(),
                              .environment = environment.get(),
                              .background = skybox.get(),
                              .shadows = &*shadows,
                              .pointShadows = &*pointShadows,
                              .settings = &settings,
                              .camera = &pending.cm,
                              .sequence = plan.sequence,
                              .occlusionDistance = occlusionDistance,
                              .first = b == 0,
                              // Occlusion only in the first batch: later ones add light.
                              .occlusion = b == 0 && fs.occlusion,
                              .coverageFrame = cameraCoverageFrame(plan),
                              .probes = fs.probeLookups ? &*probes : nullptr,
                              .writeProbeCache = b == 0 && fs.writeProbeCache,
                              .readProbeCache = b == 0 && fs.readProbeCache,
                              .cachedLights = cachedLights,
                              .writeLightCache = b == 0 && fs.writeLightCache,
                              .clearLightCache = fs.clearLightCache,
                              .lightCacheWeight = fs.lightCacheWeight,
                              .readLightCache = fs.readLightCache,
                              .accumulateFrame = fs.fused ? plan.frame : 0});
    passes::LightingBatch& batch = pending.batches.back();
    for (int k : fs.batches[b]) {
      const LightSample& s = plan.lights[static_cast<size_t>(k)];
      batch.area.push_back({.light = &lights[static_cast<size_t>(s.light)],
                            .lightIndex = s.light,
                            .weight = s.weight,
                            .shadowed = s.shadowed && scene});
    }
    if (b == 0) batch.punctual = punctual;
    if (passes::LightingPass::readsLightCache(batch)) stats.lightCacheRead = true;
  }
}

// A shadow map: of an area sample (its slot is its index in the batch) or of a punctual light
// of the first batch; or a point light's cube map.
std::function<Status()> Renderer::Impl::shadowUnit(const progressive::FrameStep& step,
                                                   const progressive::FrameSchedule& fs) {
  const int b = step.batch;
  const int shadowFrame = pending.plan.frame - 1;
  if (step.kind == progressive::StepKind::PointShadow) {
    // A cube map, rendered only when the scene has changed since the last frame.
    return [this, j = static_cast<size_t>(step.index)]() -> Status {
      passes::PunctualDraw& d = pending.batches[0].punctual[j];
      auto view = pointShadows->ensure(d.pointShadow, *scene, d.light->position);
      if (!view) return view.error();
      d.pointView = *view;
      endPass(&stats.shadowMs);
      return {};
    };
  }
  if (step.index >= 0) {
    const size_t i = static_cast<size_t>(step.index);
    const LightSample& s =
        pending.plan.lights[static_cast<size_t>(fs.batches[static_cast<size_t>(b)][i])];
    const glm::vec3 origin = render::samplePosition(lights[static_cast<size_t>(s.light)], s.point);
    return [this, b, i, origin, shadowFrame, stream = step.stream]() -> Status {
      passes::AreaSampleDraw& d = pending.batches[static_cast<size_t>(b)].area[i];
      d.view = shadows->renderLight(static_cast<int>(i), *scene, *d.light, origin,
                                    d.light->direction, shadowFrame, stream);
      ++stats.shadowPasses;
      endPass(&stats.shadowMs);
      return {};
    };
  }
  return [this, j = static_cast<size_t>(-1 - step.index), shadowFrame,
          stream = step.stream]() -> Status {
    passes::PunctualDraw& d = pending.batches[0].punctual[j];
    d.view = shadows->renderLight(d.shadowSlot, *scene, *d.light, d.light->position, d.direction,
                                  shadowFrame, stream);
    ++stats.shadowPasses;
    endPass(&stats.shadowMs);
    return {};
  };
}

// The unit of GL work for one step of the schedule.
std::function<Status()> Renderer::Impl::unitFor(const progressive::FrameStep& step,
                                                const progressive::FrameSchedule& fs,
                                                const CameraMatrices& still,
                                                float occlusionDistance) {
  using progressive::StepKind;
  const int k = pending.tiles;
  const int b = step.batch, t = step.band;
  switch (step.kind) {
    case StepKind::Prepass:
      return [this, still, t, k]() -> Status {
        if (t == 0) caches.prepassValid = false;  // until its last band is drawn
        band(t);
        prepass->render(*targets, scene.get(), still.view, still.projection,
                        cameraCoverageFrame(pending.plan));
        endBand();
        if (t == k - 1) {
          caches.prepassValid = true;
          stats.prepass = true;
        }
        endPass(&stats.prepassMs);
        return {};
      };
    case StepKind::Occlusion:
      // A quarter of the pixels (one unit for the whole image: it is small), once the prepass
      // is complete, before any lighting band.
      return [this, still, occlusionDistance, probeLookups = fs.probeLookups,
              probeCache = fs.occlusionReadsProbeCache]() -> Status {
        const ProgressiveSettings& ps = settings.progressive;
        PN_TRY(occlusionPass->trace({.targets = &*targets,
                                     .view = still.view,
                                     .projection = still.projection,
                                     .viewOrigin = still.viewOrigin,
                                     .sequence = pending.plan.sequence,
                                     .frame = pending.plan.frame,
                                     .filter = pending.plan.rayFilter,
                                     .block = options.quarterOcclusion ? 2 : 1,
                                     .occlusionDistance = occlusionDistance,
                                     .indirect = ps.screenSpaceIndirect,
                                     .indirectClamp = ps.indirectClamp,
                                     .environment = environment.get(),
                                     .environmentIntensity = settings.environmentIntensity,
                                     .environmentRotation = passes::environmentLookup(settings),
                                     .probes = probeLookups ? &*probes : nullptr,
                                     .probeCache = probeCache}));
        endPass(&stats.occlusionMs);
        return {};
      };
    case StepKind::ShadowMap:
    case StepKind::PointShadow:
      return shadowUnit(step, fs);
    case StepKind::Lighting: {
      // With transmission the lit frame is copied behind the glass, which refracts pixels from
      // anywhere on screen, skipped tiles included: those must hold this frame's light, not
      // the last frame that drew them (a frozen single sample, which showed as 8x8 blocks in a
      // glass sphere). The compose and the accumulation after it keep the tile mask.
      const bool feedsBehind = std::any_of(
          fs.steps.begin(), fs.steps.end(),
          [](const progressive::FrameStep& s) { return s.kind == StepKind::CopyBehind; });
      return [this, b, t, k, accumulate = step.accumulate, feedsBehind]() -> Status {
        band(t, !feedsBehind);
        const Status st = lighting->draw(pending.batches[static_cast<size_t>(b)]);
        if (st) {
          if (t == k - 1) ++stats.lightingPasses;
          endPass(&stats.lightingMs);
          if (accumulate) accumulateBand(t, k);
        }
        endBand();
        return st;
      };
    }
    case StepKind::CopyBehind:
      return [this]() -> Status {
        PN_TRY(lighting->copyBehind(pending.batches[0]));
        endPass(&stats.lightingMs);
        return {};
      };
    case StepKind::Compose:
      return [this, t, k]() -> Status {
        band(t);
        const Status st = lighting->composeTransmission(pending.batches[0]);
        if (st) {
          endPass(&stats.lightingMs);
          accumulateBand(t, k);
        }
        endBand();
        return st;
      };
    case StepKind::ProbeCapture:
      return [this, i = step.index]() -> Status {
        passes::ProbeCaptureInputs in{
            .scene = scene.get(),
            .environment = environment.get(),
            .lights = render::captureLights(lights, probes->lightPoint(settings.progressive.seed),
                                            settings),
            .pointShadows = &*pointShadows,
            .settings = &settings,
            .targets = &*targets,
            .newLightMap = i == 0};
        PN_TRY(probes->capture(*lighting, in));
        ++stats.probeCaptures;
        endPass(&stats.probeMs);
        return {};
      };
  }
  PN_CHECK(false, "unitFor: every step kind has a unit");
  return {};
}

void Renderer::Impl::beginFrame(const FramePlan& plan, int tiles, bool preview) {
  pending = {};
  pending.plan = plan;
  pending.preview = preview;
  pending.drawWidth = targets->width;
  pending.drawHeight = targets->height;
  if (preview) {
    const float scale = settings.progressive.previewScale;
    pending.drawWidth = std::max(1, static_cast<int>(std::lround(targets->width * scale)));
    pending.drawHeight = std::max(1, static_cast<int>(std::lround(targets->height * scale)));
  }
  pending.tiles = std::clamp(tiles, 1, std::max(1, std::min(kMaxFrameTiles, pending.drawHeight)));
  stats = {};
  stats.frame = plan.frame;
  endPass(nullptr);
  if (plan.frame == 1) {
    targets->current = 0;
    checkpointFrames.fill(0);
    tilesSkipped = false;
  }
  const Camera cam = activeCamera();
  pending.cm = cameraMatrices(cam, pending.drawWidth, pending.drawHeight, plan.jitter);
  // (Frame 1 resets the caches' counters.)
  const progressive::FrameSchedule fs =
      progressive::planFrame(plan, frameScene(preview), frameLimits(), caches);
  stats.occlusion = fs.occlusion;
  stats.probeCacheWritten = fs.writeProbeCache;
  stats.probeLookups = fs.probeLookups;
  stats.lightCacheWritten = fs.writeLightCache;
  pending.fused = fs.fused;
  const float occlusionDistance = effectiveOcclusionDistance(
      settings.progressive,
      scene && scene->bounds().valid() ? 2.0f * scene->bounds().radius() : 0.0f);
  buildBatches(fs, occlusionDistance);
  // The prepass's and the occlusion rays' camera: unjittered.
  const CameraMatrices still = cameraMatrices(cam, targets->width, targets->height, {0, 0});
  pending.units.reserve(fs.steps.size());
  for (const progressive::FrameStep& step : fs.steps) {
    pending.units.push_back(unitFor(step, fs, still, occlusionDistance));
  }
}

}  // namespace penumbra
