// Renderer::Impl, the renderer's state and frame scheduling, shared by renderer.cpp (the
// public calls that set things up and step frames), renderer_output.cpp (read-back, tone
// mapping and presenting), frame_build.cpp (a frame's units of GL work) and convergence.cpp.
// Its state comes in parts a reader can hold, each in its own header: GpuPasses (what draws),
// SceneState (what is drawn), ConvergenceState (an automatic view's measuring); Impl itself
// holds the settings, the controller, the per-view caches' counters, the frame being built
// and the statistics, and the calls that tie the parts together. Private to the library.
#pragma once

#include "penumbra/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "gl/errors.h"
#include "gl/state_guard.h"
#include "passes/camera_math.h"
#include "penumbra/environment.h"
#include "progressive/controller.h"
#include "progressive/first_frame_hold.h"
#include "progressive/first_light.h"
#include "progressive/frame_planner.h"
#include "progressive/light_cache.h"
#include "render/convergence_state.h"
#include "render/gpu_passes.h"
#include "render/light_samples.h"
#include "render/pending_frame.h"
#include "render/scene_state.h"
#include "scene/light_kinds.h"

namespace penumbra {

// The stochastic-coverage index of the camera's passes (chunks/coverage.glsl). Frame 1
// alpha-blends its BLEND surfaces (sorted back to front) so the first image already looks
// right; frames 2, 3, ... cover stochastically from index 0, so that whole blocks of
// stratified decisions end with frames 17, 33, ...
inline int cameraCoverageFrame(const FramePlan& plan) {
  return plan.frame > 1 ? plan.frame - 2 : -1;
}

struct Renderer::Impl : progressive::FrameRenderer, GpuPasses, SceneState, ConvergenceState {
  RendererOptions options;
  RenderSettings settings;
  progressive::Controller controller;
  // The per-view caches' counters (the prepass, the probe volume's and the area lights' caches),
  // advanced by the frame planner (progressive/frame_planner.h).
  progressive::CacheState caches;
  FrameStats stats;
  std::chrono::steady_clock::time_point passStart;

  // With profilePasses, finishes the GL work queued since the last call and adds its time.
  void endPass(double* ms) {
    if (!options.profilePasses) return;
    gl::finish();
    const auto now = std::chrono::steady_clock::now();
    if (ms) *ms += std::chrono::duration<double, std::milli>(now - passStart).count();
    passStart = now;
  }

  // The mean, or in the first frames of a view with stochastic transparency its mix with
  // frame 1 (progressive/first_frame_hold.h).
  Status drawDisplayed(const passes::EffectOutput& output) {
    const int n = controller.framesDone();
    const float hold = n >= 2 && holdsFirstFrame() && targets->firstFrame.color
                           ? static_cast<float>(progressive::firstFrameHold(n))
                           : 0.0f;
    if (hold > 0.0f) {
      accumulate->drawHeld(*targets, hold);
      return GpuPasses::drawDisplayed(settings, output, targets->held.color);
    }
    return GpuPasses::drawDisplayed(
        settings, output, targets->accumulation[static_cast<size_t>(targets->current)].color);
  }

  bool holdsFirstFrame() const {
    return options.firstFrameHold && scene && !scene->blended().empty();
  }

  // After frame 1 of a view with stochastic transparency: its image, kept for the display.
  Status keepFirstFrame() {
    if (!holdsFirstFrame()) return {};
    PN_TRY(targets->ensureFirstFrameHold());
    accumulate->keepFirst(*targets);
    return {};
  }
  Status ensureFrameResources() { return GpuPasses::ensureFrameResources(settings); }

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
    PN_TRY(createPasses(options));
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
    const bool probesWereWanted = probesWanted();
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
                          s.progressive.probeRelocation != previous.probeRelocation ||
                          probesWanted() != probesWereWanted;
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
    if (probesWanted()) {
      grid = progressive::placeProbes(probeBox.valid() ? probeBox : scene->bounds(),
                                      settings.progressive.probeDensity, probeCounts);
    }
    return probes->reset(grid, settings.progressive.probeRelocation);
  }
  // The volume is for light between surfaces: a scene that cannot see itself has none, unless
  // a ground shadow catches the light it reflects (ground.frag reads the probes for it).
  bool probesWanted() const {
    return settings.progressive.probeVolume && scene &&
           (seesItself || settings.shadowIntensity > 0.0f);
  }
  bool probesOn() const { return probes && probes->active() && probesWanted(); }

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
    const bool done = pending.next >= pending.units.size();
    if (done && pending.plan.frame == 1 && !pending.preview) PN_TRY(keepFirstFrame());
    return done;
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
