// The renderer: prepares GL state for a scene, environment, camera and settings, and draws
// frame n of the progressive controller's plan (FrameRenderer). The passes do the drawing.
#include "penumbra/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "gl/capabilities.h"
#include "gl/errors.h"
#include "passes/fullscreen_pass.h"
#include "passes/shadow_pass.h"
#include "passes/targets.h"
#include "penumbra/environment.h"
#include "progressive/controller.h"
#include "render/camera_math.h"
#include "gpu/gpu_environment.h"
#include "gpu/gpu_scene.h"

namespace penumbra {
namespace {

// Texture units, fixed for every program.
constexpr int kUnitEnvCube = 5, kUnitLut = 6, kUnitPrepass = 7, kUnitAccumulated = 8,
              kUnitShadow = 9;
constexpr int kMaxAreaPerBatch = passes::kMaxShadowMaps;
constexpr int kMaxPunctual = 8;

// The stochastic-coverage index of the camera's passes (chunks/coverage.glsl). Frame 1
// alpha-blends its BLEND surfaces (sorted back to front) so the first image already looks
// right; frames 2, 3, ... cover stochastically from index 0, so that whole blocks of
// stratified decisions end with frames 17, 33, ...
int cameraCoverageFrame(const FramePlan& plan) {
  return plan.frame > 1 ? plan.frame - 2 : -1;
}

// GL rows run bottom-up; Image rows top-down. Flips in place and takes the buffer: a
// 1280x720 float image is 15 MB, and fresh pages cost more than the copy on some machines.
Image flipRows(std::vector<float> data, int w, int h, int channels) {
  const auto row = static_cast<std::ptrdiff_t>(w) * channels;
  for (int y = 0; y < h / 2; ++y) {
    std::swap_ranges(data.begin() + y * row, data.begin() + (y + 1) * row,
                     data.begin() + (h - 1 - y) * row);
  }
  Image img;
  img.width = w;
  img.height = h;
  img.channels = channels;
  img.pixels = std::move(data);
  return img;
}

}  // namespace

struct Renderer::Impl : progressive::FrameRenderer {
  RendererOptions options;
  gl::Capabilities caps;
  gl::ShaderLibrary library;
  RenderSettings settings;
  progressive::Controller controller;
  std::optional<passes::RenderTargets> targets;
  std::optional<passes::ShadowPass> shadows;
  std::optional<passes::FullscreenPass> accumulate, tonemap, background;
  gl::Program* lighting = nullptr;
  gl::Program* prepassProgram = nullptr;
  std::unique_ptr<GpuScene> scene;
  std::vector<Light> lights;
  std::unique_ptr<GpuEnvironment> environment;
  Camera camera;
  bool hasCamera = false;
  bool prepassValid = false;
  FrameStats stats;
  gl::Texture2D dummy2d;
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
    // Compile every lighting variant up front: no frame pays for a shader compile.
    for (int v = 0; v < 8; ++v) {
      auto lit = lightingProgram(v & 1, v & 2, v & 4);
      if (!lit) return lit.error();
    }
    auto pre = library.program("mesh.vert", "prepass.frag");
    if (!pre) return pre.error();
    prepassProgram = *pre;
    for (auto [slot, file] :
         {std::pair{&accumulate, "accumulate.frag"}, std::pair{&tonemap, "tonemap.frag"}}) {
      auto p = passes::FullscreenPass::create(library, file);
      if (!p) return p.error();
      slot->emplace(std::move(*p));
    }
    auto bg = passes::FullscreenPass::create(library, "background.frag", /*farPlane=*/true);
    if (!bg) return bg.error();
    background.emplace(std::move(*bg));
    auto d = gl::Texture2D::create({.width = 1, .height = 1, .format = gl::PixelFormat::RGBA8});
    if (!d) return d.error();
    const uint8_t black[4] = {0, 0, 0, 0};
    d->upload(0, black, gl::DataType::UInt8);
    dummy2d = std::move(*d);
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
    }
    if (shadowResize) {
      shadows.reset();
      auto sp = passes::ShadowPass::create(library, s.progressive.shadowMapSize);
      if (!sp) return sp.error();
      shadows.emplace(std::move(*sp));
    }
    controller.setSettings(s.progressive);
    updateDarkness();
    if (resize || restartNeeded) controller.invalidate();
    return {};
  }

  void setLights() {
    std::vector<progressive::LightInfo> infos;
    for (const Light& l : lights) {
      progressive::LightInfo info;
      info.shape = l.type == LightType::Rect   ? progressive::LightShape::Rect
                   : l.type == LightType::Disk ? progressive::LightShape::Disk
                                               : progressive::LightShape::Point;
      info.aspect = l.height > 0 ? l.width / l.height : 1.0f;
      infos.push_back(info);
    }
    controller.setLights(infos);
  }

  Result<gl::Program*> lightingProgram(bool occlusion, bool area, bool punctual) {
    return library.program("mesh.vert", "lighting.frag",
                           {{"PN_OCCLUSION", occlusion ? "1" : "0"},
                            {"PN_AREA", area ? "1" : "0"},
                            {"PN_PUNCTUAL", punctual ? "1" : "0"}});
  }

  Camera activeCamera() const { return hasCamera ? camera : defaultCameraForBounds(); }
  Camera defaultCameraForBounds() const {
    Scene empty;
    if (scene) empty.bounds = scene->bounds();
    return defaultCamera(empty);
  }

  glm::mat3 envRotation() const {
    // The environment turns by +angle about Y: look up directions turned by -angle.
    return glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(-settings.environmentRotation),
                                 glm::vec3(0, 1, 0)));
  }

  void drawList(const gl::Program& program, const std::vector<DrawItem>& items, bool material,
                gl::PipelineState state) {
    for (const DrawItem& item : items) {
      const Material& m = scene->material(item.material).source;
      state.cull = m.doubleSided ? gl::Cull::None : gl::Cull::Back;
      state.frontFaceClockwise = item.mirrored;
      gl::apply(state);
      GpuScene::bindTransform(program, item);
      if (material) scene->bindMaterial(program, item.material);
      item.primitive->vao.draw(gl::Primitive::Triangles, item.primitive->indexCount);
    }
  }

  void renderPrepass(const CameraMatrices& cm, int coverageFrame) {
    targets->prepass.framebuffer.bind();
    gl::setViewport(0, 0, targets->width, targets->height);
    gl::apply({});
    gl::clearBufferFloat(0, 0, 0, 0, 0);
    gl::clearDepth(1.0f);
    prepassProgram->use();
    prepassProgram->set("uViewProj", cm.projection * cm.view);
    prepassProgram->set("uView", cm.view);
    prepassProgram->set("uCoverageFrame", coverageFrame);
    prepassProgram->set("uCoverageStream", 0);
    if (scene) {
      drawList(*prepassProgram, scene->opaque(), true, {});
      drawList(*prepassProgram, scene->blended(), true, {});
    }
    prepassValid = true;
  }

  void setLightingUniforms(const CameraMatrices& cm, const glm::mat4& jitteredViewProj,
                           const FramePlan& plan, bool occlusion) {
    const gl::Program& p = *lighting;
    p.use();
    p.set("uViewProj", jitteredViewProj);
    p.set("uViewOrigin", cm.viewOrigin);
    environment->bind(p, kUnitEnvCube, kUnitLut, settings.environmentIntensity, envRotation());
    // From frame 2 the accumulation holds at least frame 1: its radiance can be reused.
    p.set("uIndirectEnabled", settings.progressive.screenSpaceIndirect ? 1 : 0);
    p.set("uIndirectClamp",
          settings.progressive.indirectClamp > 0.0f ? settings.progressive.indirectClamp : 3.0e38f);
    (occlusion ? targets->prepass.color : dummy2d).bind(kUnitPrepass);
    targets->accumulation[static_cast<size_t>(targets->current)].color.bind(kUnitAccumulated);
    p.set("uPrepass", kUnitPrepass);
    p.set("uAccumulated", kUnitAccumulated);
    p.set("uOcclusionDistance", settings.progressive.occlusionDistance);
    p.set("uView", cm.view);
    p.set("uProjection", cm.projection);
    p.set("uViewportSize", glm::vec2(targets->width, targets->height));
    p.set("uSequence", plan.sequence);
    shadows->bind(p, kUnitShadow);
  }

  // World position of a light sample on the light's true surface.
  static glm::vec3 samplePosition(const Light& l, glm::vec2 u) {
    if (l.type == LightType::Disk) {
      glm::vec2 d = progressive::concentricDisk(u) * (0.5f * l.width);
      return l.position + d.x * l.right + d.y * l.up;
    }
    if (l.type == LightType::Rect) {
      return l.position + (u.x - 0.5f) * l.width * l.right + (u.y - 0.5f) * l.height * l.up;
    }
    return l.position;
  }

  Status renderFrame(const FramePlan& plan) override {
    stats = {};
    stats.frame = plan.frame;
    endPass(nullptr);
    if (plan.frame == 1) targets->current = 0;
    const Camera cam = activeCamera();
    const CameraMatrices cm = cameraMatrices(cam, targets->width, targets->height, plan.jitter);
    if (plan.frame == 1) prepassValid = false;
    // BLEND surfaces cover the pixels differently each frame: the occlusion rays must see
    // this frame's coverage, so the prepass is redrawn every frame when there are any.
    const bool coverageChanges = scene && !scene->blended().empty();
    if (plan.occlusion && (plan.renderPrepass || !prepassValid || coverageChanges)) {
      renderPrepass(cameraMatrices(cam, targets->width, targets->height, {0, 0}),
                    cameraCoverageFrame(plan));
      stats.prepass = true;
      endPass(&stats.prepassMs);
    }
    stats.occlusion = plan.occlusion && prepassValid;
    const glm::mat4 viewProj = cm.projection * cm.view;

    // Split this frame's light samples: shadowed area samples go in batches of up to four.
    std::vector<const LightSample*> area, punctual;
    for (const LightSample& s : plan.lights) {
      if (s.light < 0 || s.light >= static_cast<int>(lights.size())) continue;
      (lights[static_cast<size_t>(s.light)].isArea() ? area : punctual).push_back(&s);
    }
    int shadowStream = 0;  // each shadow map of the frame decides coverage on its own
    const int batches =
        std::max(1, static_cast<int>((area.size() + kMaxAreaPerBatch - 1) / kMaxAreaPerBatch));
    for (int b = 0; b < batches; ++b) {
      std::vector<passes::ShadowView> views;
      std::vector<const LightSample*> batch;
      for (size_t i = static_cast<size_t>(b) * kMaxAreaPerBatch;
           i < area.size() && batch.size() < kMaxAreaPerBatch; ++i) {
        batch.push_back(area[i]);
      }
      std::stable_sort(batch.begin(), batch.end(), [](const LightSample* x, const LightSample* y) {
        return x->light < y->light;
      });
      for (size_t i = 0; i < batch.size(); ++i) {
        const Light& l = lights[static_cast<size_t>(batch[i]->light)];
        if (batch[i]->shadowed && scene) {
          views.push_back(shadows->render(static_cast<int>(i), *scene,
                                          samplePosition(l, batch[i]->point), l.direction, l.up,
                                          plan.frame - 1, ++shadowStream));
          ++stats.shadowPasses;
          endPass(&stats.shadowMs);
        } else {
          views.push_back({});
        }
      }
      PN_TRY(drawLighting(plan, cm, viewProj, b == 0, batch, views,
                          b == 0 ? punctual : std::vector<const LightSample*>{}));
      ++stats.lightingPasses;
      endPass(&stats.lightingMs);
    }

    // Accumulate: mean_n = mean_{n-1} + (x_n - mean_{n-1}) / n.
    const int prev = targets->current, next = 1 - targets->current;
    targets->accumulation[static_cast<size_t>(next)].framebuffer.bind();
    gl::setViewport(0, 0, targets->width, targets->height);
    const gl::Program& acc = accumulate->begin();
    targets->accumulation[static_cast<size_t>(prev)].color.bind(0);
    targets->frame.color.bind(1);
    acc.set("uPrevious", 0);
    acc.set("uCurrent", 1);
    acc.set("uWeight", 1.0f / static_cast<float>(plan.frame));
    accumulate->draw();
    endPass(&stats.accumulateMs);
    targets->current = next;
    return gl::checkError("frame " + std::to_string(plan.frame));
  }

  // The environment behind the scene: drawn after the opaque geometry at the far plane, so
  // only uncovered pixels pay for it.
  void drawBackground(const glm::mat4& viewProj) {
    if (!settings.showBackground) return;
    const gl::Program& bg = background->begin(/*depthTest=*/true);
    environment->bind(bg, kUnitEnvCube, kUnitLut, settings.environmentIntensity, envRotation());
    bg.set("uInvViewProj", glm::inverse(viewProj));
    bg.set("uBackgroundBlur", settings.backgroundBlur);
    background->draw();
  }

  Status drawLighting(const FramePlan& plan, const CameraMatrices& cm, const glm::mat4& viewProj,
                      bool first, const std::vector<const LightSample*>& batch,
                      const std::vector<passes::ShadowView>& views,
                      const std::vector<const LightSample*>& punctual) {
    targets->frame.framebuffer.bind();
    gl::setViewport(0, 0, targets->width, targets->height);
    if (first) {
      gl::apply({});
      gl::clearBufferFloat(0, 0, 0, 0, 1);
      gl::clearDepth(1.0f);
    }
    if (!scene) {
      if (first) drawBackground(viewProj);
      return Status{};
    }
    // Occlusion only in the first batch: extra batches add direct light alone.
    const bool occlusion = first && plan.occlusion && prepassValid;
    auto program = lightingProgram(occlusion, !batch.empty(), !punctual.empty());
    if (!program) return program.error();
    lighting = *program;
    setLightingUniforms(cm, viewProj, plan, occlusion);
    const gl::Program& p = *lighting;
    p.set("uEnvWeight", first ? 1.0f : 0.0f);
    const int coverageFrame = cameraCoverageFrame(plan);
    p.set("uCoverageFrame", coverageFrame);
    p.set("uCoverageStream", 0);
    // Area-light samples of this batch.
    std::vector<glm::vec3> pos, dir, right, up, radiance;
    std::vector<glm::vec4> shape;
    std::vector<int> lightIds;
    std::vector<glm::mat4> shadowMatrices(passes::kMaxShadowMaps, glm::mat4(1.0f));
    std::vector<glm::vec4> shadowParams(passes::kMaxShadowMaps, glm::vec4(0.0f));
    for (size_t i = 0; i < batch.size(); ++i) {
      const Light& l = lights[static_cast<size_t>(batch[i]->light)];
      lightIds.push_back(batch[i]->light);
      pos.push_back(l.position);
      dir.push_back(l.direction);
      right.push_back(l.right);
      up.push_back(l.up);
      const bool shadowed = batch[i]->shadowed;
      shape.emplace_back(l.width, l.height, l.type == LightType::Disk ? 1.0f : 0.0f,
                         shadowed ? static_cast<float>(i) : -1.0f);
      radiance.push_back(l.color * l.intensity * batch[i]->weight);
      if (shadowed) {
        shadowMatrices[i] = views[i].matrix;
        shadowParams[i] = views[i].params;
      }
    }
    p.set("uAreaCount", static_cast<int>(batch.size()));
    p.set("uAreaLight", std::span<const int>(lightIds));
    p.set("uAreaPos", std::span<const glm::vec3>(pos));
    p.set("uAreaDir", std::span<const glm::vec3>(dir));
    p.set("uAreaRight", std::span<const glm::vec3>(right));
    p.set("uAreaUp", std::span<const glm::vec3>(up));
    p.set("uAreaShape", std::span<const glm::vec4>(shape));
    p.set("uAreaRadiance", std::span<const glm::vec3>(radiance));
    p.set("uShadowMatrix", std::span<const glm::mat4>(shadowMatrices));
    p.set("uShadowParams", std::span<const glm::vec4>(shadowParams));
    // Punctual lights (first batch only).
    std::vector<glm::vec4> ppos, pdir;
    std::vector<glm::vec3> pcol;
    std::vector<glm::vec2> cone;
    for (const LightSample* s : punctual) {
      if (ppos.size() >= kMaxPunctual) break;
      const Light& l = lights[static_cast<size_t>(s->light)];
      const float type = l.type == LightType::Point  ? 0.0f
                         : l.type == LightType::Spot ? 1.0f
                                                     : 2.0f;
      ppos.emplace_back(l.position, type);
      pdir.emplace_back(l.direction, l.range);
      pcol.push_back(l.color * l.intensity * s->weight);
      const float cosOuter = std::cos(l.outerConeAngle), cosInner = std::cos(l.innerConeAngle);
      const float scale = 1.0f / std::max(cosInner - cosOuter, 1e-4f);
      cone.emplace_back(scale, -cosOuter * scale);
    }
    p.set("uPunctualCount", static_cast<int>(ppos.size()));
    p.set("uPunctualPos", std::span<const glm::vec4>(ppos));
    p.set("uPunctualDir", std::span<const glm::vec4>(pdir));
    p.set("uPunctualColor", std::span<const glm::vec3>(pcol));
    p.set("uPunctualCone", std::span<const glm::vec2>(cone));
    gl::PipelineState opaque;
    if (!first) {
      opaque.depthTest = gl::DepthTest::LessEqual;
      opaque.depthWrite = false;
      opaque.blend = gl::Blend::Additive;
    }
    targets->frame.framebuffer.bind();
    drawList(p, scene->opaque(), true, opaque);
    // Stochastic coverage: BLEND surfaces are drawn like opaque ones, minus the fragments
    // this frame does not keep, in every batch (the same decisions each time).
    if (coverageFrame >= 0) drawList(p, scene->blended(), true, opaque);
    if (first) drawBackground(viewProj);
    if (first && coverageFrame < 0 && !scene->blended().empty()) {
      std::vector<DrawItem> sorted = scene->blended();
      std::sort(sorted.begin(), sorted.end(), [&](const DrawItem& a, const DrawItem& b) {
        // Back to front: by distance from the eye, or along the parallel rays (orthographic).
        auto far = [&](const glm::vec3& c) {
          return cm.viewOrigin.w > 0.5f ? glm::distance(c, cm.position)
                                        : -glm::dot(c, glm::vec3(cm.viewOrigin));
        };
        return far(a.center) > far(b.center);
      });
      p.use();  // the background pass left its own program bound
      drawList(p, sorted, true, {.depthWrite = false, .blend = gl::Blend::Alpha});
    }
    return {};
  }
};

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

Result<std::unique_ptr<Renderer>> Renderer::create(const RendererOptions& options) {
  std::unique_ptr<Renderer> r(new Renderer());
  r->impl_->options = options;
  PN_TRY(r->impl_->init());
  return r;
}

Status Renderer::setScene(const Scene& scene) {
  auto gs = GpuScene::create(scene);
  if (!gs) return gs.error();
  impl_->scene = std::move(*gs);
  impl_->lights = scene.lights;
  impl_->setLights();
  impl_->controller.invalidate();
  return {};
}

Status Renderer::setEnvironment(const PackedEnvironment& environment) {
  auto env = GpuEnvironment::create(environment);
  if (!env) return env.error();
  impl_->environment = std::move(*env);
  // The mean radiance is the first SH coefficient times Y00.
  const glm::vec3 mean = environment.sh.c[0] * 0.282095f;
  impl_->environmentMean = std::max(mean.r, std::max(mean.g, mean.b));
  impl_->updateDarkness();
  impl_->controller.invalidate();
  return {};
}

void Renderer::setCamera(const Camera& camera) {
  impl_->camera = camera;
  impl_->hasCamera = true;
  impl_->controller.invalidate();
}

Status Renderer::setSettings(const RenderSettings& settings) {
  return impl_->applySettings(settings, false);
}

Result<int> Renderer::step() {
  return impl_->controller.step(*impl_);
}
void Renderer::restart() {
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
const FrameStats& Renderer::lastFrame() const {
  return impl_->stats;
}
const RenderSettings& Renderer::settings() const {
  return impl_->settings;
}
std::string Renderer::capabilityReport() const {
  return impl_->caps.report();
}

Result<Image> Renderer::readRadiance() {
  auto& t = *impl_->targets;
  auto data = t.accumulation[static_cast<size_t>(t.current)].framebuffer.readRgbaFloat(
      0, 0, 0, t.width, t.height);
  PN_TRY(gl::checkError("reading the accumulated image"));
  return flipRows(std::move(data), t.width, t.height, 4);
}

Status Renderer::toneMap() {
  auto& t = *impl_->targets;
  t.display.framebuffer.bind();
  gl::setViewport(0, 0, t.width, t.height);
  impl_->drawToneMapped();
  return gl::checkError("tone mapping");
}

void Renderer::finish() {
  gl::finish();
}

Result<Image> Renderer::readDisplay() {
  PN_TRY(toneMap());
  auto& t = *impl_->targets;
  auto bytes = t.display.framebuffer.readRgba8(0, 0, 0, t.width, t.height);
  PN_TRY(gl::checkError("reading the displayed image"));
  // Converted straight into the flipped float image: one allocation, no intermediate copy.
  Image img;
  img.width = t.width;
  img.height = t.height;
  img.channels = 4;
  img.pixels.resize(bytes.size());
  const size_t row = static_cast<size_t>(t.width) * 4;
  for (int y = 0; y < t.height; ++y) {
    const uint8_t* src = bytes.data() + static_cast<size_t>(t.height - 1 - y) * row;
    float* dst = img.pixels.data() + static_cast<size_t>(y) * row;
    for (size_t i = 0; i < row; ++i) dst[i] = static_cast<float>(src[i]) * (1.0f / 255.0f);
  }
  return img;
}

Status Renderer::present(int canvasWidth, int canvasHeight) {
  if (canvasWidth <= 0 || canvasHeight <= 0) {
    return makeError("present: canvas size " + std::to_string(canvasWidth) + "x" +
                     std::to_string(canvasHeight) + " is empty");
  }
  gl::Framebuffer::bindDefault();
  gl::setViewport(0, 0, canvasWidth, canvasHeight);
  impl_->drawToneMapped();
  return gl::checkError("presenting to the canvas");
}

}  // namespace penumbra
