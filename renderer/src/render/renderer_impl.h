// Renderer::Impl, the renderer's state and frame scheduling, shared by renderer.cpp (the
// public calls that set things up and step frames) and renderer_output.cpp (read-back, tone
// mapping and presenting). Private to the library.
#pragma once

#include "penumbra/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "gl/capabilities.h"
#include "gl/errors.h"
#include "gl/state_guard.h"
#include "gpu/gpu_environment.h"
#include "gpu/gpu_scene.h"
#include "passes/accumulate_pass.h"
#include "passes/camera_math.h"
#include "passes/fullscreen_pass.h"
#include "passes/lighting_pass.h"
#include "passes/limits.h"
#include "passes/occlusion_pass.h"
#include "passes/prepass.h"
#include "passes/probe_volume.h"
#include "passes/shadow_pass.h"
#include "passes/targets.h"
#include "penumbra/environment.h"
#include "progressive/controller.h"
#include "progressive/light_cache.h"
#include "render/light_samples.h"

namespace penumbra {

// The stochastic-coverage index of the camera's passes (chunks/coverage.glsl). Frame 1
// alpha-blends its BLEND surfaces (sorted back to front) so the first image already looks
// right; frames 2, 3, ... cover stochastically from index 0, so that whole blocks of
// stratified decisions end with frames 17, 33, ...
inline int cameraCoverageFrame(const FramePlan& plan) {
  return plan.frame > 1 ? plan.frame - 2 : -1;
}

struct Renderer::Impl : progressive::FrameRenderer {
  RendererOptions options;
  gl::Capabilities caps;
  gl::ShaderLibrary library;
  RenderSettings settings;
  progressive::Controller controller;
  std::optional<passes::RenderTargets> targets;
  std::optional<passes::ShadowPass> shadows;
  std::optional<passes::PointShadowPass> pointShadows;
  std::optional<passes::Prepass> prepass;
  std::optional<passes::LightingPass> lighting;
  std::optional<passes::AccumulatePass> accumulate;
  std::optional<passes::OcclusionPass> occlusionPass;
  std::optional<passes::FullscreenPass> tonemap;
  std::optional<passes::ProbeVolume> probes;  // absent without renderable half floats
  Bounds probeBox;                            // the scene file's, else the scene's bounds
  glm::ivec3 probeCounts{0};                  // the scene file's (0: from the density)
  std::unique_ptr<GpuScene> scene;
  std::vector<Light> lights;  // the scene's, then the environment's sun if it has one
  std::vector<Light> sceneLights;
  std::optional<ibl::Sun> sun;  // as stored with the environment (unrotated, unscaled)
  ibl::SkyDistribution sky;     // the environment without its sun, for sky shadows
  Light skySample;              // this frame's sky-shadow sample (punctual draws point to it)
  std::unique_ptr<GpuEnvironment> environment;
  Camera camera;
  bool hasCamera = false;
  bool prepassValid = false;
  int probeCacheFrame = -1;  // the frame that last wrote the probe cache (-1: none this view)
  double probeCacheCaptures = 0.0;  // the volume's mean captures a probe at that frame
  int lightCacheWritten = 0;        // frames of this view in the area lights' cache
  FrameStats stats;
  float environmentMean = 0.0f;  // mean radiance of the environment (before intensity)
  std::chrono::steady_clock::time_point passStart;

  // With profilePasses, finishes the GL work queued since the last call and adds its time.
  void endPass(double* ms) {
    if (!options.profilePasses) return;
    gl::finish();
    const auto now = std::chrono::steady_clock::now();
    if (ms) *ms += std::chrono::duration<double, std::milli>(now - passStart).count();
    passStart = now;
  }

  // Exposure, tone mapping and sRGB of the running mean into the bound framebuffer and
  // viewport (the display target, or the canvas).
  void drawToneMapped() {
    const gl::Program& p = tonemap->begin();
    targets->accumulation[static_cast<size_t>(targets->current)].color.bind(0);
    p.set("uRadiance", 0);
    p.set("uExposureScale", std::exp2(settings.exposure));
    p.set("uToneMapper", static_cast<int>(settings.toneMapper));
    tonemap->draw();
  }

  // With a black environment nothing is visible before direct light: start it at frame 2.
  void updateDarkness() {
    controller.setDarkEnvironment(environmentMean * settings.environmentIntensity < 1e-6f);
  }

  Status init() {
    caps = gl::queryCapabilities(options.desktopGl, {.forceHalfFloat = options.forceHalfFloat});
    library.setCommonDefines(passes::limitDefines());
    auto lit = passes::LightingPass::create(library);
    if (!lit) return lit.error();
    lighting.emplace(std::move(*lit));
    auto pre = passes::Prepass::create(library);
    if (!pre) return pre.error();
    prepass.emplace(std::move(*pre));
    auto acc = passes::AccumulatePass::create(library);
    if (!acc) return acc.error();
    accumulate.emplace(std::move(*acc));
    auto occ = passes::OcclusionPass::create(library);
    if (!occ) return occ.error();
    occlusionPass.emplace(std::move(*occ));
    auto tm = passes::FullscreenPass::create(library, "tonemap.frag");
    if (!tm) return tm.error();
    tonemap.emplace(std::move(*tm));
    if (caps.colorBufferHalfFloat) {
      auto pv = passes::ProbeVolume::create(library);
      if (!pv) return pv.error();
      probes.emplace(std::move(*pv));
    }
    environment = nullptr;
    auto env = GpuEnvironment::create(uniformEnvironment(glm::vec3(0.0f)));
    if (!env) return env.error();
    environment = std::move(*env);
    return applySettings(settings, true);
  }

  Status applySettings(const RenderSettings& s, bool force) {
    PN_TRY(validate(s));
    const bool resize =
        force || !targets || s.width != settings.width || s.height != settings.height;
    const bool shadowResize =
        force || !shadows || s.progressive.shadowMapSize != settings.progressive.shadowMapSize;
    const bool restartNeeded = force || s.environmentIntensity != settings.environmentIntensity ||
                               s.environmentRotation != settings.environmentRotation ||
                               s.showBackground != settings.showBackground ||
                               s.backgroundBlur != settings.backgroundBlur;
    const ProgressiveSettings previous = settings.progressive;
    settings = s;
    if (resize) {
      targets.reset();
      auto t = passes::RenderTargets::create(
          s.width, s.height, caps.accumulationFormat,
          // Half floats hold the prepass (view normal, linear depth) well enough for the
          // occlusion march's 0.2 % depth tolerance, at half the bandwidth of its random reads.
          caps.colorBufferHalfFloat ? gl::PixelFormat::RGBA16F : caps.accumulationFormat);
      if (!t) return t.error();
      targets.emplace(std::move(*t));
      prepassValid = false;
      probeCacheFrame = -1;
    }
    if (shadowResize) {
      shadows.reset();
      auto sp = passes::ShadowPass::create(library, s.progressive.shadowMapSize);
      if (!sp) return sp.error();
      shadows.emplace(std::move(*sp));
      // Cube maps: six faces each, so at most 1024 pixels a face (24 MB a light at 1024).
      auto pp =
          passes::PointShadowPass::create(library, std::min(s.progressive.shadowMapSize, 1024));
      if (!pp) return pp.error();
      pointShadows.emplace(std::move(*pp));
    }
    const bool relayout = force || s.progressive.probeVolume != previous.probeVolume ||
                          s.progressive.probeDensity != previous.probeDensity;
    controller.setSettings(s.progressive);
    if (sun && restartNeeded) setLights();  // the sun turns and scales with the environment
    if (relayout) {
      PN_TRY(layoutProbes());
    } else if (restartNeeded && probes) {
      probes->clear();  // the light the volume holds changed
    }
    updateDarkness();
    if (resize || restartNeeded) controller.invalidate();
    return {};
  }

  void setLights() {
    lights = sceneLights;
    if (sun) lights.push_back(render::sunLight(*sun, settings));
    const size_t sunIndex = sun ? lights.size() - 1 : lights.size();
    std::vector<progressive::LightInfo> infos;
    for (const Light& l : lights) {
      progressive::LightInfo info;
      // A directional light's samples spread over its angular size: a disk of directions.
      info.shape = l.type == LightType::Rect ? progressive::LightShape::Rect
                   : l.type == LightType::Disk || l.type == LightType::Directional
                       ? progressive::LightShape::Disk
                       : progressive::LightShape::Point;
      info.aspect = l.height > 0 ? l.width / l.height : 1.0f;
      info.fromFrameOne = infos.size() == sunIndex;
      infos.push_back(info);
    }
    controller.setLights(infos);
  }

  // The probe grid over the scene's (or the scene file's) box; empty when the volume is off.
  Status layoutProbes() {
    if (!probes) return {};
    progressive::ProbeGrid grid;
    if (settings.progressive.probeVolume && scene) {
      grid = progressive::placeProbes(probeBox.valid() ? probeBox : scene->bounds(),
                                      settings.progressive.probeDensity, probeCounts);
    }
    return probes->reset(grid);
  }
  bool probesOn() const {
    return probes && probes->active() && settings.progressive.probeVolume && scene;
  }

  Camera activeCamera() const { return hasCamera ? camera : defaultCameraForBounds(); }
  Camera defaultCameraForBounds() const {
    Scene empty;
    if (scene) empty.bounds = scene->bounds();
    return defaultCamera(empty);
  }

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
  PendingFrame pending;
  int frameTiles = 1;

  // Restricts drawing to band t of the pending frame (no-op unsplit). Bands cover the drawn
  // part bottom-up, rows [t h / k, (t + 1) h / k).
  void band(int t) const {
    if (pending.tiles <= 1) return;
    const int h = pending.drawHeight, k = pending.tiles;
    const int y0 = t * h / k, y1 = (t + 1) * h / k;
    gl::setScissor(0, y0, pending.drawWidth, y1 - y0);
  }

  void endBand() const {
    if (pending.tiles > 1) gl::disableScissor();
  }
  // Band t of k of the frame's accumulation (frame 1 becomes the mean by a swap instead; a
  // preview, drawn whole, stands in for it upsampled).
  void accumulateBand(int t, int k) {
    if (pending.preview) {
      accumulate->upsampleFirst(*targets, pending.drawWidth, pending.drawHeight);
      targets->current = 1 - targets->current;
      endPass(&stats.accumulateMs);
    } else if (pending.plan.frame == 1) {
      if (t == k - 1) targets->takeFrameAsMean();  // mean_1 = x_1: no pass needed
    } else if (pending.fused) {
      if (t == k - 1) targets->current = 1 - targets->current;  // drawn by the lighting pass
      stats.fusedAccumulation = true;
    } else {
      accumulate->draw(*targets, pending.plan.frame);
      if (t == k - 1) targets->current = 1 - targets->current;  // the new mean
      endPass(&stats.accumulateMs);
    }
  }

  // preview: frame 1 drawn at previewScale as a stand-in for the mean (Renderer::preview).
  void beginFrame(const FramePlan& plan, int tiles, bool preview = false) {
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
    const int m = settings.progressive.frames;
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
          .probes = probesOn() ? &*probes : nullptr,
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

  // Runs the pending frame's next unit (all of them unsplit). True once the frame is done.
  Result<bool> runPart() {
    const bool all = pending.tiles <= 1;
    do {
      PN_TRY(pending.units[pending.next++]());
    } while (all && pending.next < pending.units.size());
    PN_TRY(gl::checkError("frame " + std::to_string(pending.plan.frame)));
    return pending.next >= pending.units.size();
  }

  // Frame 1 of the plan as a reduced preview (Renderer::preview); the caller restarted the
  // controller.
  Status renderPreview() {
    if (!targets) return makeError("preview: the renderer has no targets");
    beginFrame(controller.plan().front(), 1, true);
    auto done = runPart();
    if (!done) return done.error();
    return {};
  }

  Status renderFrame(const FramePlan& plan) override {
    beginFrame(plan, 1);
    auto done = runPart();
    if (!done) return done.error();
    return {};
  }

  Result<bool> renderFramePart(const FramePlan& plan, bool begin) override {
    if (begin || pending.next >= pending.units.size()) beginFrame(plan, frameTiles);
    return runPart();
  }
};

}  // namespace penumbra
