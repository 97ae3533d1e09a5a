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
#include "passes/effect_chain.h"
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
#include "progressive/first_light.h"
#include "progressive/frame_planner.h"
#include "progressive/light_cache.h"
#include "render/light_samples.h"
#include "scene/light_kinds.h"

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
  std::optional<passes::FullscreenPass> tonemapFiltered;  // made on first use (an upscale)
  passes::EffectChain effects;                            // post effects before tone mapping
  std::optional<passes::FullscreenPass> convergence;      // made on an automatic view's first use
  std::optional<passes::FullscreenPass> checkpointSnapshot;  // likewise
  // The checkpoint whose displayed image each of targets->checkpoints holds (0: none this view).
  std::array<int, progressive::kKeptCheckpoints> checkpointFrames{};
  std::optional<passes::FullscreenPass> tileMaskPass;  // made on first use
  // The frame's stencil marks tiles this view no longer shades (skipTiles): the image units
  // (lighting, compose, accumulation) test it. Cleared by frame 1.
  bool tilesSkipped = false;
  std::optional<passes::ProbeVolume> probes;  // absent without renderable half floats
  Bounds probeBox;                            // the scene file's, else the scene's bounds
  glm::ivec3 probeCounts{0};                  // the scene file's (0: from the density)
  std::unique_ptr<GpuScene> scene;
  // Some surface of the scene faces another (scene/self_visibility.h): without, the probe
  // volume and the occlusion rays are skipped, as they could only give what is there without.
  bool seesItself = true;
  std::vector<Light> lights;  // the scene's, then the environment's sun if it has one
  std::vector<Light> sceneLights;
  std::optional<ibl::Sun> sun;  // as stored with the environment (unrotated, unscaled)
  ibl::SkyDistribution sky;     // the environment without its sun, for sky shadows
  Light skySample;              // this frame's sky-shadow sample (punctual draws point to it)
  std::unique_ptr<GpuEnvironment> environment;
  std::unique_ptr<GpuEnvironment> skybox;  // the view's background (setSkybox); null: environment
  Camera camera;
  bool hasCamera = false;
  // The per-view caches' counters (the prepass, the probe volume's and the area lights' caches),
  // advanced by the frame planner (progressive/frame_planner.h).
  progressive::CacheState caches;
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

  // The radiance the display shows: the mean after the post effects (passes/effect_chain.h).
  // Runs them (into their own targets): call before binding the display's framebuffer.
  Result<const gl::Texture2D*> displayedRadiance() {
    const auto& mean = targets->accumulation[static_cast<size_t>(targets->current)].color;
    return effects.run(library, mean, targets->width, targets->height, settings,
                       caps.colorBufferHalfFloat);
  }
  // Exposure, tone mapping and sRGB of `radiance` into the bound framebuffer and viewport (the
  // display target, or the canvas); `filtered`: the viewport is larger than the image, which is
  // then interpolated between texels.
  Status drawToneMapped(const gl::Texture2D& radiance, bool filtered = false) {
    if (filtered && !tonemapFiltered) {
      auto tm =
          passes::FullscreenPass::create(library, "tonemap.frag", false, {{"PN_FILTERED", "1"}});
      if (!tm) return tm.error();
      tonemapFiltered.emplace(std::move(*tm));
    }
    const passes::FullscreenPass& pass = filtered ? *tonemapFiltered : *tonemap;
    const gl::Program& p = pass.begin();
    radiance.bind(0);
    p.set("uRadiance", 0);
    p.set("uExposureScale", std::exp2(settings.exposure));
    p.set("uToneMapper", static_cast<int>(settings.toneMapper));
    pass.draw();
    // The mean read here is the target the next frame's fused lighting draws into: a browser's
    // GL took every such draw for a feedback loop while it stayed bound (20 % slower frames).
    gl::Texture2D::unbind(0);
    return {};
  }

  // First light (distributeSamples): where the environment alone would give frame 1 less than
  // half of the scene's light (progressive::environmentShare), frame 1 evaluates the scene's
  // lights.
  void updateFirstLight() {
    controller.setFirstLight(
        progressive::environmentShare(sceneLights, environmentMean * settings.environmentIntensity,
                                      scene ? scene->bounds() : Bounds{}) < 0.5f);
  }

  // FrameRenderer: the tiles' RMS and largest change since the last checkpoint, and the tiles
  // no longer shaded (render/convergence.cpp).
  Result<progressive::TileChanges> measureTiles(int frame) override;
  Status skipTiles(std::span<const uint8_t> mask) override;

  Status init() {
    caps = gl::queryCapabilities(options.desktopGl, {.forceHalfFloat = options.forceHalfFloat});
    PN_TRY(checkTextureUnits(caps.maxTextureUnits));
    library.setCommonDefines(passes::commonDefines());
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
    const bool resize = force || s.width != settings.width || s.height != settings.height;
    const bool shadowResize =
        force || s.progressive.shadowMapSize != settings.progressive.shadowMapSize;
    const bool restartNeeded = force || s.environmentIntensity != settings.environmentIntensity ||
                               s.environmentRotation != settings.environmentRotation ||
                               s.showBackground != settings.showBackground ||
                               s.backgroundBlur != settings.backgroundBlur;
    const ProgressiveSettings previous = settings.progressive;
    settings = s;
    if (resize) {
      targets.reset();  // made again by the next frame (ensureFrameResources)
      caches.prepassValid = false;
      caches.probeCacheFrame = -1;
    }
    if (shadowResize) {
      shadows.reset();
      pointShadows.reset();
    }
    const bool relayout = force || s.progressive.probeVolume != previous.probeVolume ||
                          s.progressive.probeDensity != previous.probeDensity ||
                          s.progressive.probeRelocation != previous.probeRelocation;
    controller.setSettings(s.progressive);
    if (sun && restartNeeded) setLights();  // the sun turns and scales with the environment
    if (relayout) {
      PN_TRY(layoutProbes());
    } else if (restartNeeded && probes) {
      probes->clear();  // the light the volume holds changed
    }
    updateFirstLight();
    if (resize || restartNeeded) controller.invalidate();
    return {};
  }

  // The frame targets and the shadow maps are made when something first draws or reads them,
  // not when settings change: a viewer sets its canvas's size and then a scene's settings before
  // its first frame, and made at each step the 1280x720 defaults took the phone page's GPU
  // memory at start-up to 116 MB (56 MB now). An allocation that fails is reported by the call
  // that needed it.
  Status ensureFrameResources() {
    if (!targets) {
      auto t = passes::RenderTargets::create(
          settings.width, settings.height, caps.accumulationFormat,
          // Half floats hold the prepass (view normal, linear depth) well enough for the
          // occlusion march's 0.2 % depth tolerance, at half the bandwidth of its random reads.
          caps.colorBufferHalfFloat ? gl::PixelFormat::RGBA16F : caps.accumulationFormat);
      if (!t) return t.error();
      targets.emplace(std::move(*t));
    }
    if (!shadows) {
      auto sp = passes::ShadowPass::create(library, settings.progressive.shadowMapSize);
      if (!sp) return sp.error();
      shadows.emplace(std::move(*sp));
    }
    if (!pointShadows) {
      // Cube maps: six faces each, so at most 1024 pixels a face (24 MB a light at 1024).
      auto pp = passes::PointShadowPass::create(library,
                                                std::min(settings.progressive.shadowMapSize, 1024));
      if (!pp) return pp.error();
      pointShadows.emplace(std::move(*pp));
    }
    return {};
  }

  void setLights() {
    lights = sceneLights;
    if (sun) lights.push_back(render::sunLight(*sun, settings));
    const size_t sunIndex = sun ? lights.size() - 1 : lights.size();
    std::vector<progressive::LightInfo> infos;
    for (const Light& l : lights) {
      progressive::LightInfo info;
      // (A directional light's samples spread over its angular size: a disk of directions.)
      info.shape = lightKind(l.type).samples;
      info.aspect = l.height > 0 ? l.width / l.height : 1.0f;
      info.fromFrameOne = infos.size() == sunIndex;
      infos.push_back(info);
    }
    controller.setLights(infos);
    updateFirstLight();
  }

  // The probe grid over the scene's (or the scene file's) box; empty when the volume is off.
  Status layoutProbes() {
    if (!probes) return {};
    progressive::ProbeGrid grid;
    if (settings.progressive.probeVolume && scene && seesItself) {
      grid = progressive::placeProbes(probeBox.valid() ? probeBox : scene->bounds(),
                                      settings.progressive.probeDensity, probeCounts);
    }
    return probes->reset(grid, settings.progressive.probeRelocation);
  }
  bool probesOn() const {
    return probes && probes->active() && settings.progressive.probeVolume && scene && seesItself;
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
  // Also where the frame's units over the image apply the tile mask (adaptive frames), unless
  // `maskTiles` is false: a unit whose output other pixels read this frame must draw them all.
  void band(int t, bool maskTiles = true) const {
    if (tilesSkipped && maskTiles) gl::setStencil(gl::StencilMode::SkipMarked);
    if (pending.tiles <= 1) return;
    const int h = pending.drawHeight, k = pending.tiles;
    const int y0 = t * h / k, y1 = (t + 1) * h / k;
    gl::setScissor(0, y0, pending.drawWidth, y1 - y0);
  }

  void endBand() const {
    if (tilesSkipped) gl::setStencil(gl::StencilMode::Off);
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
  // (render/frame_build.cpp: the frame planner's steps as units of GL work.)
  void beginFrame(const FramePlan& plan, int tiles, bool preview = false);
  // The planner's view of the scene and settings, and the limits and switches it plans with.
  progressive::FrameScene frameScene(bool preview) const;
  progressive::FrameLimits frameLimits() const;
  void buildBatches(const progressive::FrameSchedule& fs, float occlusionDistance);
  std::function<Status()> shadowUnit(const progressive::FrameStep& step,
                                     const progressive::FrameSchedule& fs);
  std::function<Status()> unitFor(const progressive::FrameStep& step,
                                  const progressive::FrameSchedule& fs, const CameraMatrices& still,
                                  float occlusionDistance);

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
    PN_TRY(ensureFrameResources());
    beginFrame(controller.plan().front(), 1, true);
    auto done = runPart();
    if (!done) return done.error();
    return {};
  }

  Status renderFrame(const FramePlan& plan) override {
    PN_TRY(ensureFrameResources());
    beginFrame(plan, 1);
    auto done = runPart();
    if (!done) return done.error();
    return {};
  }

  Result<bool> renderFramePart(const FramePlan& plan, bool begin) override {
    if (begin || pending.next >= pending.units.size()) {
      PN_TRY(ensureFrameResources());
      beginFrame(plan, frameTiles);
    }
    return runPart();
  }
};

}  // namespace penumbra
