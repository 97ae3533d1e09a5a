// The renderer: prepares GL state for a scene, environment, camera and settings, and draws
// frame n of the progressive controller's plan (FrameRenderer). The passes do the drawing.
#include <cmath>
#include <string>

#include "gl/memory.h"
#include "render/renderer_impl.h"
#include "scene/self_visibility.h"

namespace penumbra {

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

Result<std::unique_ptr<Renderer>> Renderer::create(const RendererOptions& options) {
  std::unique_ptr<Renderer> r(new Renderer());
  r->impl_->options = options;
  gl::StateGuard guard(options.preserveHostState);
  PN_TRY(r->impl_->init());
  return r;
}

Status Renderer::setScene(const Scene& scene) {
  gl::StateGuard guard(impl_->options.preserveHostState);
  auto gs = GpuScene::create(scene);
  if (!gs) return gs.error();
  // One check for the whole upload where allocations defer theirs (WebGL: gl::checkAllocation).
  PN_TRY(gl::checkError("uploading the scene"));
  impl_->scene = std::move(*gs);
  impl_->rig = scene.rig;
  impl_->restBounds = impl_->scene->bounds();
  if (impl_->pointShadows) impl_->pointShadows->invalidate();
  impl_->sceneLights = scene.lights;
  impl_->setLights();  // after the scene: first light weighs the lights by its bounds
  impl_->probeBox = scene.probeBox;
  impl_->probeCounts = scene.probeCounts;
  impl_->seesItself = surfacesSeeEachOther(scene);
  PN_TRY(impl_->layoutProbes());
  impl_->controller.invalidate();
  return {};
}

Status Renderer::setVariant(int index) {
  if (!impl_->scene) return makeError("setVariant: no scene (call setScene first)");
  if (index < -1 || index >= impl_->scene->variantCount()) {
    return makeError("no material variant " + std::to_string(index) + ": the scene has " +
                     std::to_string(impl_->scene->variantCount()));
  }
  gl::StateGuard guard(impl_->options.preserveHostState);
  PN_TRY(impl_->scene->selectVariant(index));
  // Alpha cut-outs and transmission may differ: point-light shadow maps are drawn again; the
  // probes keep their places (the geometry is the same) but gather the new materials' light.
  if (impl_->pointShadows) impl_->pointShadows->invalidate();
  if (impl_->probes) impl_->probes->clear();
  impl_->controller.invalidate();
  return {};
}

Status Renderer::setEnvironment(const PackedEnvironment& environment) {
  gl::StateGuard guard(impl_->options.preserveHostState);
  auto env = GpuEnvironment::create(environment);
  if (!env) return env.error();
  PN_TRY(gl::checkError("uploading the environment"));
  impl_->environment = std::move(*env);
  // The mean radiance is the first SH coefficient times Y00.
  const glm::vec3 mean = environment.sh.c[0] * 0.282095f;
  impl_->environmentMean = std::max(mean.r, std::max(mean.g, mean.b));
  impl_->sun = environment.sun;
  impl_->sky = environment.specular.mipCount() > 0
                   ? ibl::SkyDistribution::build(environment.specular, 16, /*upperOnly=*/true)
                   : ibl::SkyDistribution();
  impl_->setLights();  // also decides first light, which weighs the environment's mean
  if (impl_->probes) impl_->probes->clear();
  impl_->controller.invalidate();
  return {};
}

Status Renderer::setSkybox(const PackedEnvironment* skybox) {
  gl::StateGuard guard(impl_->options.preserveHostState);
  if (!skybox) {
    impl_->skybox = nullptr;
  } else {
    auto env = GpuEnvironment::create(*skybox);
    if (!env) return env.error();
    PN_TRY(gl::checkError("uploading the skybox"));
    impl_->skybox = std::move(*env);
  }
  impl_->controller.invalidate();
  return {};
}

Status Renderer::setPose(int animation, float time) {
  const PoseLayer layer{animation, time, 1.0f};
  return setPose(std::span<const PoseLayer>(&layer, 1));
}

Status Renderer::setPose(std::span<const PoseLayer> layers) {
  if (!impl_->scene) return makeError("setPose: no scene (call setScene first)");
  if (!impl_->rig) {
    return makeError("setPose: the scene was loaded without playback (LoadOptions::playback)");
  }
  for (const PoseLayer& l : layers) {
    if (l.animation < -1 || l.animation >= static_cast<int>(impl_->rig->clips.size())) {
      return makeError("no animation " + std::to_string(l.animation) + ": the scene has " +
                       std::to_string(impl_->rig->clips.size()));
    }
    if (!std::isfinite(l.time)) return makeError("setPose: the time must be a finite number");
    if (!(l.weight >= 0.0f) || !std::isfinite(l.weight)) {
      return makeError("setPose: a layer's weight must be a finite number >= 0");
    }
  }
  gl::StateGuard guard(impl_->options.preserveHostState);
  if (!impl_->deform) {
    auto pass = passes::DeformPass::create(impl_->library);
    if (!pass) return pass.error();
    impl_->deform.emplace(std::move(*pass));
  }
  const Pose pose = poseRig(*impl_->rig, layers);
  PN_TRY(impl_->scene->pose(pose));
  PN_TRY(impl_->deform->run(*impl_->scene, pose));
  // The geometry moved: point-light shadow maps are drawn again, and the probes are laid over
  // the pose's bounds (as for the still of that pose) and gather anew.
  if (impl_->pointShadows) impl_->pointShadows->invalidate();
  PN_TRY(impl_->layoutProbes());
  impl_->controller.invalidate();
  return {};
}

void Renderer::setCamera(const Camera& camera) {
  impl_->camera = camera;
  impl_->hasCamera = true;
  impl_->controller.invalidate();
}

Status Renderer::setSettings(const RenderSettings& settings) {
  gl::StateGuard guard(impl_->options.preserveHostState);
  return impl_->applySettings(settings, false);
}

Result<int> Renderer::step() {
  gl::StateGuard guard(impl_->options.preserveHostState);
  return impl_->controller.step(*impl_);
}
Result<FramePart> Renderer::stepPart() {
  gl::StateGuard guard(impl_->options.preserveHostState);
  auto r = impl_->controller.stepPart(*impl_);
  if (!r) return r.error();
  // Unsplit, the frame's units ran as one part.
  const auto& p = impl_->pending;
  const bool whole = p.tiles <= 1;
  return FramePart{.frame = r->frame,
                   .done = r->done,
                   .part = r->frame == 0 ? 0
                           : whole       ? 1
                                         : static_cast<int>(p.next),
                   .parts = r->frame == 0 ? 0
                            : whole       ? 1
                                          : static_cast<int>(p.units.size())};
}
Status Renderer::preview() {
  gl::StateGuard guard(impl_->options.preserveHostState);
  impl_->controller.invalidate();
  return impl_->renderPreview();
}
void Renderer::setFrameTiles(int tiles) {
  impl_->frameTiles = std::clamp(tiles, 1, kMaxFrameTiles);
}
int Renderer::frameTiles() const {
  return impl_->frameTiles;
}
void Renderer::restart() {
  // Starting over is starting over: the probe volume too (camera moves keep it).
  if (impl_->probes) impl_->probes->clear();
  impl_->controller.invalidate();
}
bool Renderer::converged() const {
  return impl_->controller.converged();
}
int Renderer::framesDone() const {
  return impl_->controller.framesDone();
}
int Renderer::totalFrames() const {
  return impl_->controller.totalFrames();
}
ConvergenceInfo Renderer::convergence() const {
  const auto& c = impl_->controller;
  const auto& e = c.estimate();
  return {.automatic = c.automatic(),
          .measured = e.measured,
          .converged = e.converged,
          .frame = e.frame,
          .error = e.error,
          .tileError = e.tileError,
          .convergedTiles = e.convergedTiles,
          .expectedFrames = c.expectedFrames(),
          .skippedTiles = e.skippedTiles,
          .decay = e.decay};
}
const FrameStats& Renderer::lastFrame() const {
  return impl_->stats;
}
ProbeVolumeInfo Renderer::probeVolumeInfo() const {
  ProbeVolumeInfo info;
  if (!impl_->probesOn()) return info;
  const auto& g = impl_->probes->grid();
  info.probes = g.count();
  for (int a = 0; a < 3; ++a) info.counts[a] = g.counts[a];
  info.bytes = impl_->probes->memoryBytes();
  info.meanCaptures = impl_->probes->meanCaptures();
  info.moved = impl_->probes->movedProbes();
  return info;
}
const RenderSettings& Renderer::settings() const {
  return impl_->settings;
}
int64_t Renderer::gpuMemoryBytes() {
  return gl::liveBytes();
}
int Renderer::maxTextureSize() const {
  return impl_->caps.maxTextureSize;
}
std::string Renderer::capabilityReport() const {
  return impl_->caps.report();
}

}  // namespace penumbra
