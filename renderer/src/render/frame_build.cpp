// Renderer::Impl::beginFrame: frame n of the plan as a list of units of GL work (prepass,
// occlusion rays, shadow maps, lighting batches band by band, accumulation, probe captures),
// run by runPart() one at a time or all at once (docs/architecture.md, "In parts").
#include "render/renderer_impl.h"

namespace penumbra {

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
  if (plan.frame == 1) targets->current = 0;
  const Camera cam = activeCamera();
  pending.cm = cameraMatrices(cam, pending.drawWidth, pending.drawHeight, plan.jitter);
  if (plan.frame == 1) {
    prepassValid = false;
    probeCacheFrame = -1;
    lightCacheWritten = 0;
    checkpointFrame = 0;
    tilesSkipped = false;
  }
  auto& units = pending.units;
  const int k = pending.tiles;
  // BLEND surfaces cover the pixels differently each frame: the occlusion rays must see
  // this frame's coverage, so the prepass is redrawn every frame when there are any.
  const bool coverageChanges = scene && !scene->blended().empty();
  const bool drawPrepass =
      plan.occlusion && (plan.renderPrepass || !prepassValid || coverageChanges);
  // The prepass's and the occlusion rays' camera: unjittered.
  const CameraMatrices still = cameraMatrices(cam, targets->width, targets->height, {0, 0});
  if (drawPrepass) {
    for (int t = 0; t < k; ++t) {
      units.push_back([this, still, t, k]() -> Status {
        if (t == 0) prepassValid = false;  // until its last band is drawn
        band(t);
        prepass->render(*targets, scene.get(), still.view, still.projection,
                        cameraCoverageFrame(pending.plan));
        endBand();
        if (t == k - 1) {
          prepassValid = true;
          stats.prepass = true;
        }
        endPass(&stats.prepassMs);
        return {};
      });
    }
  }
  const bool occlusion = plan.occlusion && (drawPrepass || prepassValid);
  stats.occlusion = occlusion;
  const float occlusionDistance = effectiveOcclusionDistance(
      settings.progressive,
      scene && scene->bounds().valid() ? 2.0f * scene->bounds().radius() : 0.0f);
  if (occlusion) {
    // This frame's diffuse occlusion rays, at a quarter of the pixels, once the prepass is
    // complete: one unit for the whole image (it is small), before any lighting band.
    units.push_back([this, still, occlusionDistance]() -> Status {
      const ProgressiveSettings& ps = settings.progressive;
      PN_TRY(occlusionPass->trace({.targets = &*targets,
                                   .view = still.view,
                                   .projection = still.projection,
                                   .sequence = pending.plan.sequence,
                                   .frame = pending.plan.frame,
                                   .block = options.quarterOcclusion ? 2 : 1,
                                   .occlusionDistance = occlusionDistance,
                                   .indirect = ps.screenSpaceIndirect,
                                   .indirectClamp = ps.indirectClamp}));
      endPass(&stats.occlusionMs);
      return {};
    });
  }
  // The probe volume's per-view cache, read in between remakes (progressive::remakeProbeCache:
  // ever more rarely as the volume converges).
  const bool probeCache = occlusion && probesOn() && options.probeCache;
  const double captured = probesOn() ? probes->meanCaptures() : 0.0;
  const int since = probeCacheFrame < 0 ? -1 : plan.frame - probeCacheFrame;
  const bool writeProbeCache =
      probeCache && progressive::remakeProbeCache(since, captured, probeCacheCaptures);
  if (writeProbeCache) {
    probeCacheFrame = plan.frame;
    probeCacheCaptures = captured;
  }
  stats.probeCacheWritten = writeProbeCache;
  // An empty volume (no capture yet: the first frame after a reset) answers nothing, so frames
  // without occlusion rays skip its per-pixel lookup; later frames keep it, so that the
  // per-view cache's remakes stay on their schedule.
  const bool probeLookups = probesOn() && (occlusion || probes->captures() > 0);
  stats.probeLookups = probeLookups;
  // The area lights' per-view cache (progressive/light_cache.h): every area light of the scene
  // (up to kMaxCachedLights), opaque scenes only (BLEND surfaces cover differently each frame).
  std::vector<passes::AreaSampleDraw> cachedLights;
  if (options.lightCache && scene && scene->blended().empty()) {
    for (size_t i = 0; i < lights.size(); ++i) {
      if (lights[i].isArea()) cachedLights.push_back({&lights[i], static_cast<int>(i)});
    }
    if (cachedLights.size() > static_cast<size_t>(passes::kMaxCachedLights)) {
      cachedLights.clear();
    }
  }
  // An automatic view sizes the cache as a view of 128 frames (its stopping point is unknown).
  const int m = settings.progressive.frames > 0 ? settings.progressive.frames : 128;
  const bool writeLightCache =
      !cachedLights.empty() && progressive::writesLightCache(plan.frame, lightCacheWritten, m);
  const bool readLightCache =
      !cachedLights.empty() && progressive::lightCacheReady(lightCacheWritten, m);
  const bool clearLightCache = writeLightCache && lightCacheWritten == 0;
  if (writeLightCache) ++lightCacheWritten;
  stats.lightCacheWritten = writeLightCache;
  // Split this frame's light samples: area samples go in batches of up to kMaxShadowMaps.
  std::vector<const LightSample*> area;
  std::vector<passes::PunctualDraw> punctual;
  for (const LightSample& s : pending.plan.lights) {
    if (s.light < 0 || s.light >= static_cast<int>(lights.size())) continue;
    const Light& l = lights[static_cast<size_t>(s.light)];
    // Frame 1 becomes the mean without the accumulation's guard against non-finite samples:
    // a light that can only give NaN (first light) is left out of it.
    if (plan.frame == 1 && !(std::isfinite(l.intensity) && std::isfinite(l.color.r) &&
                             std::isfinite(l.color.g) && std::isfinite(l.color.b))) {
      continue;
    }
    if (l.isArea()) {
      area.push_back(&s);
    } else {
      punctual.push_back({&l, s.weight, render::punctualDirection(l, s.point, settings)});
    }
  }
  // Sky shadows: one direction of the sunless environment, by luminance, from the frames with
  // occlusion on (the diffuse term it corrects is then a per-frame estimate anyway).
  if (plan.occlusion && settings.progressive.skyShadows && scene && !sky.empty() &&
      environmentMean * settings.environmentIntensity > 0.0f &&
      punctual.size() < static_cast<size_t>(passes::kMaxPunctualLights)) {
    skySample = render::skyLight(sky.sample(plan.skyPoint), settings);
    passes::PunctualDraw pd{&skySample, 1.0f, skySample.direction};
    pd.skyLoss = true;
    punctual.push_back(pd);
  }
  constexpr size_t kBatch = passes::kMaxShadowMaps;
  int shadowStream = 0;  // each shadow map of the frame decides coverage on its own
  // Spot and directional samples (first batch only) take shadow maps before area samples;
  // the first point lights take cube maps, rendered once per scene.
  size_t punctualMaps = 0;
  int pointMaps = 0;
  for (passes::PunctualDraw& pd : punctual) {
    if (!scene) break;
    if (pd.light->type == LightType::Point) {
      if (pointMaps < passes::kMaxPointShadows) pd.pointShadow = pointMaps++;
    } else if (punctualMaps < kBatch) {
      pd.shadowSlot = static_cast<int>(punctualMaps++);
    }
  }
  const size_t firstBatch = kBatch - punctualMaps;
  const size_t batches =
      area.size() <= firstBatch ? 1 : 1 + (area.size() - firstBatch + kBatch - 1) / kBatch;
  pending.batches.reserve(batches);
  const bool transmissive = scene && !scene->transmissive().empty();
  // One batch and nothing drawn over it: it adds its sample to the mean as it draws.
  pending.fused = options.fusedAccumulation && batches == 1 && !transmissive && plan.frame > 1 &&
                  !pending.preview;
  for (size_t b = 0; b < batches; ++b) {
    pending.batches.push_back(passes::LightingBatch{
        .targets = &*targets,
        .drawWidth = pending.drawWidth,
        .drawHeight = pending.drawHeight,
        .scene = scene.get(),
        .environment = environment.get(),
        .shadows = &*shadows,
        .pointShadows = &*pointShadows,
        .settings = &settings,
        .camera = &pending.cm,
        .sequence = plan.sequence,
        .occlusionDistance = occlusionDistance,
        .first = b == 0,
        // Occlusion only in the first batch: later ones add light.
        .occlusion = b == 0 && occlusion,
        .coverageFrame = cameraCoverageFrame(plan),
        .probes = probeLookups ? &*probes : nullptr,
        .writeProbeCache = b == 0 && writeProbeCache,
        .readProbeCache = b == 0 && probeCache,
        .cachedLights = cachedLights,
        .writeLightCache = b == 0 && writeLightCache,
        .clearLightCache = clearLightCache,
        .lightCacheWeight = 1.0f / static_cast<float>(progressive::lightCacheFrames(m)),
        .readLightCache = readLightCache,
        .accumulateFrame = pending.fused ? plan.frame : 0});
    passes::LightingBatch& batch = pending.batches.back();
    const size_t from = b == 0 ? 0 : firstBatch + (b - 1) * kBatch;
    const size_t to = b == 0 ? firstBatch : from + kBatch;
    std::vector<const LightSample*> samples(
        area.begin() + static_cast<std::ptrdiff_t>(std::min(from, area.size())),
        area.begin() + static_cast<std::ptrdiff_t>(std::min(to, area.size())));
    // Sorted by light: the shader computes a light's unshadowed shading once for its samples.
    std::stable_sort(
        samples.begin(), samples.end(),
        [](const LightSample* x, const LightSample* y) { return x->light < y->light; });
    const int shadowFrame = plan.frame - 1;
    for (size_t i = 0; i < samples.size(); ++i) {
      const LightSample& s = *samples[i];
      const Light& l = lights[static_cast<size_t>(s.light)];
      passes::AreaSampleDraw draw{.light = &l, .lightIndex = s.light, .weight = s.weight};
      if (s.shadowed && scene) {
        draw.shadowed = true;
        const glm::vec3 origin = render::samplePosition(l, s.point);
        units.push_back([this, b, i, origin, shadowFrame, stream = ++shadowStream]() -> Status {
          passes::AreaSampleDraw& d = pending.batches[b].area[i];
          d.view = shadows->renderLight(static_cast<int>(i), *scene, *d.light, origin,
                                        d.light->direction, shadowFrame, stream);
          ++stats.shadowPasses;
          endPass(&stats.shadowMs);
          return {};
        });
      }
      batch.area.push_back(draw);
    }
    if (b == 0) {
      // Their maps follow the batch's area samples.
      const int firstSlot = static_cast<int>(batch.area.size());
      for (size_t j = 0; j < punctual.size(); ++j) {
        passes::PunctualDraw& pd = punctual[j];
        if (pd.pointShadow >= 0) {
          // A cube map, rendered only when the scene has changed since the last frame.
          units.push_back([this, j]() -> Status {
            passes::PunctualDraw& d = pending.batches[0].punctual[j];
            auto view = pointShadows->ensure(d.pointShadow, *scene, d.light->position);
            if (!view) return view.error();
            d.pointView = *view;
            endPass(&stats.shadowMs);
            return {};
          });
          continue;
        }
        if (pd.shadowSlot < 0) continue;
        pd.shadowSlot += firstSlot;
        units.push_back([this, j, shadowFrame, stream = ++shadowStream]() -> Status {
          passes::PunctualDraw& d = pending.batches[0].punctual[j];
          d.view = shadows->renderLight(d.shadowSlot, *scene, *d.light, d.light->position,
                                        d.direction, shadowFrame, stream);
          ++stats.shadowPasses;
          endPass(&stats.shadowMs);
          return {};
        });
      }
      batch.punctual = punctual;
    }
    if (passes::LightingPass::readsLightCache(batch)) stats.lightCacheRead = true;
    // Without transmissive surfaces the last batch's band also accumulates; with them the
    // accumulation waits for their compose (below).
    const bool accumulateHere = b + 1 == batches && !transmissive;
    for (int t = 0; t < k; ++t) {
      units.push_back([this, b, t, k, accumulateHere]() -> Status {
        band(t);
        const Status st = lighting->draw(pending.batches[b]);
        if (st) {
          if (t == k - 1) ++stats.lightingPasses;
          endPass(&stats.lightingMs);
          if (accumulateHere) accumulateBand(t, k);
        }
        endBand();
        return st;
      });
    }
  }
  if (transmissive) {
    // Transmissive surfaces look through a copy of the whole frame (a refracted ray may land
    // in another band): the copy is a unit of its own after every band's lighting, then each
    // band composes them and accumulates.
    units.push_back([this]() -> Status {
      PN_TRY(lighting->copyBehind(pending.batches[0]));
      endPass(&stats.lightingMs);
      return {};
    });
    for (int t = 0; t < k; ++t) {
      units.push_back([this, t, k]() -> Status {
        band(t);
        const Status st = lighting->composeTransmission(pending.batches[0]);
        if (st) {
          endPass(&stats.lightingMs);
          accumulateBand(t, k);
        }
        endBand();
        return st;
      });
    }
  }
  // Probe captures, the frame's last units, one probe each (a frame dropped part-way keeps
  // the captures it made; the web viewer's time budget sees probe-sized parts): every frame
  // but the first, which captures only until the volume has settled (so it still fills while a
  // viewer orbits and frame 1 is all it draws), and never before the first frame after a
  // reset (the first image comes as fast as without the volume).
  if (probesOn() &&
      (plan.frame >= 2 ||
       (probes->captures() > 0 && probes->meanCaptures() < progressive::kProbeSettledCaptures))) {
    // How many: progressive::probeCapturesThisFrame (more while the volume is young, fewer
    // once it has settled).
    const int n = progressive::probeCapturesThisFrame(settings.progressive.probesPerFrame,
                                                      probes->grid().count(),
                                                      probes->meanCaptures(), plan.frame);
    for (int i = 0; i < n; ++i) {
      units.push_back([this, i]() -> Status {
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
      });
    }
  }
}

}  // namespace penumbra
