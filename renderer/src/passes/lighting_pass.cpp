#include "passes/lighting_pass.h"

#include <algorithm>
#include <span>

#include <glm/gtc/matrix_transform.hpp>

#include "passes/limits.h"
#include "passes/probe_volume.h"
#include "passes/scene_draw.h"

namespace penumbra::passes {

// The environment turns by +angle about Y: look up directions turned by -angle.
glm::mat3 environmentLookup(const RenderSettings& s) {
  return glm::mat3(
      glm::rotate(glm::mat4(1.0f), glm::radians(-s.environmentRotation), glm::vec3(0, 1, 0)));
}

namespace {

// The part of the targets a batch draws (LightingBatch::drawWidth).
glm::ivec2 drawnSize(const LightingBatch& b) {
  return b.drawWidth > 0 ? glm::ivec2(b.drawWidth, b.drawHeight)
                         : glm::ivec2(b.targets->width, b.targets->height);
}

// The environment is drawn behind the scene (not with a transparent background).
bool backgroundShown(const LightingBatch& b) {
  return b.settings->showBackground && !b.settings->transparentBackground;
}

// tan(angular radius) of a directional light's disk (0: a point at infinity, or not
// directional).
float directionalDisk(const Light& l, const RenderSettings& s) {
  if (l.type != LightType::Directional) return 0.0f;
  const float diameter =
      l.angularDiameter > 0.0f ? l.angularDiameter : glm::radians(s.progressive.directionalAngle);
  return std::tan(0.5f * diameter);
}

}  // namespace

Result<LightingPass> LightingPass::create(gl::ShaderLibrary& library) {
  LightingPass pass;
  pass.library_ = &library;
  auto depth = library.program("mesh.vert", "prepass.frag");
  if (!depth) return depth.error();
  pass.depthOnly_ = *depth;
  for (const int accumulate : {0, 1}) {
    auto bg =
        FullscreenPass::create(library, "background.frag", /*farPlane=*/true,
                               {{"PN_ACCUMULATE", std::to_string(accumulate)}, {"PN_BLUR", "0"}});
    if (!bg) return bg.error();
    pass.backgrounds_[static_cast<size_t>(accumulate * 2)].emplace(std::move(*bg));
  }
  auto d = gl::Texture2D::create({.width = 1, .height = 1, .format = gl::PixelFormat::RGBA8});
  if (!d) return d.error();
  const uint8_t black[4] = {0, 0, 0, 0};
  d->upload(0, black, gl::DataType::UInt8);
  pass.dummy_ = std::move(*d);
  return pass;
}

PunctualSample LightingPass::sampleOf(const PunctualDraw& d, const RenderSettings& s) {
  return punctualSample(*d.light, !d.skyLoss && directionalDisk(*d.light, s) > 0.0f, d.skyLoss);
}

uint32_t LightingPass::punctualKinds(const LightingBatch& b) {
  uint32_t kinds = 0;
  for (const PunctualDraw& d : b.punctual) kinds |= sampleBit(sampleOf(d, *b.settings));
  return kinds;
}

int LightingPass::lightCacheLayer(const LightingBatch& b, int lightIndex) {
  const auto it = std::find_if(b.cachedLights.begin(), b.cachedLights.end(),
                               [&](const AreaSampleDraw& c) { return c.lightIndex == lightIndex; });
  return it == b.cachedLights.end() ? -1 : static_cast<int>(it - b.cachedLights.begin());
}

bool LightingPass::readsLightCache(const LightingBatch& b) {
  if (!b.readLightCache || b.area.empty() || !b.targets->lightCache) return false;
  for (const PunctualDraw& d : b.punctual) {
    if (d.pointShadow >= 0) return false;
  }
  return std::all_of(b.area.begin(), b.area.end(), [&](const AreaSampleDraw& a) {
    return lightCacheLayer(b, a.lightIndex) >= 0;
  });
}

bool LightingPass::readsProbeCache(const LightingBatch& b) {
  return b.readProbeCache && b.probes && b.targets->probeCache;
}

void LightingPass::setSampleCounts(LightingVariant& v, const LightingBatch& b) {
  static_assert(kMaxShadowMaps < 8 && kMaxPunctualLights < 16, "counts overflow their bits");
  if (v.area) {
    const size_t n = std::min(b.area.size(), static_cast<size_t>(kMaxShadowMaps));
    for (size_t i = 0; i < n; ++i) {
      if (i == 0 || b.area[i].lightIndex != b.area[i - 1].lightIndex) v.areaStarts |= 1u << i;
    }
    v.areaCount = static_cast<uint32_t>(n);
  }
  if (v.punctual) {
    v.punctualCount =
        static_cast<uint32_t>(std::min(b.punctual.size(), static_cast<size_t>(kMaxPunctualLights)));
  }
}

LightingVariant LightingPass::variant(const LightingBatch& b, bool occlusion, bool area,
                                      bool punctual) {
  LightingVariant v;
  v.occlusion = occlusion;
  v.area = area;
  v.punctual = punctual;
  v.probes = b.probes && b.probes->active();
  v.probeCache = readsProbeCache(b);
  v.pointShadows =
      punctual && std::any_of(b.punctual.begin(), b.punctual.end(),
                              [](const PunctualDraw& d) { return d.pointShadow >= 0; });
  v.punctualKinds = punctual ? punctualKinds(b) : 0u;
  v.lightCache = area && readsLightCache(b);
  v.accumulate = b.accumulateFrame > 0;
  setSampleCounts(v, b);
  return v;
}

Result<gl::Program*> LightingPass::program(LightingVariant v, const MaterialFeatures& features) {
  // Smooth materials evaluate their lights every frame (MaterialFeatures::lightCacheable).
  if (!features.lightCacheable) v.lightCache = 0;
  const ProgramKey key(v, features);
  const std::array<uint64_t, 2> packed = key.key();
  if (auto it = programs_.find(packed); it != programs_.end()) return it->second;
  auto p = library_->program("mesh.vert", v.fragmentFile(), key.defines());
  if (!p) return p.error();
  programs_.emplace(packed, *p);
  return *p;
}

Status LightingPass::drawByMaterial(const LightingVariant& v, const GpuScene& scene,
                                    const std::vector<DrawItem>& items, gl::PipelineState state,
                                    const std::function<void(const gl::Program&)>& setup,
                                    int instances) {
  std::vector<const gl::Program*> ready;  // set up in this call
  const gl::Program* current = nullptr;
  const bool cacheWrite = v.lightCacheWrite != 0;
  for (const DrawItem& item : items) {
    const MaterialFeatures& features = scene.material(item.material).features;
    if (cacheWrite && !features.lightCacheable) continue;  // they never read it
    auto p = program(v, features);
    if (!p) return p.error();
    if (*p != current) {
      current = *p;
      if (std::find(ready.begin(), ready.end(), current) == ready.end()) {
        setup(*current);
        ready.push_back(current);
      } else {
        current->use();
        current->rebind();  // its units held another program's textures since
      }
    }
    if (instances > 0) {
      drawItemBothSides(*current, scene, item, state, instances);
    } else {
      drawItem(*current, scene, item, true, state);
    }
  }
  return {};
}

void LightingPass::setUniforms(const gl::Program& p, const LightingBatch& b,
                               const glm::mat3& envRotation) {
  setViewUniforms(p, b, envRotation);
  setShadowSlots(p, b);
  setAreaUniforms(p, b);
  setPunctualUniforms(p, b);
  if (b.accumulateFrame > 0) setAccumulation(p, b);
}

// The camera, the environment, the occlusion rays and the caches, the shadow maps' textures.
void LightingPass::setViewUniforms(const gl::Program& p, const LightingBatch& b,
                                   const glm::mat3& envRotation) {
  const RenderSettings& s = *b.settings;
  const CameraMatrices& cm = *b.camera;
  p.use();
  p.set("uViewProj", cm.projection * cm.view);
  p.set("uViewOrigin", cm.viewOrigin);
  b.environment->bind(p, s.environmentIntensity, envRotation);
  // From frame 2 the accumulation holds at least frame 1: its radiance can be reused.
  p.set("uIndirectEnabled", s.progressive.screenSpaceIndirect ? 1 : 0);
  p.set("uIndirectClamp",
        s.progressive.indirectClamp > 0.0f ? s.progressive.indirectClamp : 3.0e38f);
  p.bind("uPrepass", b.occlusion ? b.targets->prepass.color : dummy_);
  p.bind("uOcclusion",
         b.occlusion && b.targets->occlusion.color ? b.targets->occlusion.color : dummy_);
  p.set("uOcclusionBlock", std::max(b.targets->occlusionBlock, 1));
  p.bind("uAccumulated", b.targets->accumulation[static_cast<size_t>(b.targets->current)].color);
  p.set("uOcclusionDistance", b.occlusionDistance);
  p.set("uView", cm.view);
  p.set("uProjection", cm.projection);
  p.set("uViewportSize", glm::vec2(drawnSize(b)));
  p.set("uSequence", b.sequence);
  b.shadows->bind(p);
  b.pointShadows->bind(p);
  p.set("uEnvWeight", b.first ? 1.0f : 0.0f);
  p.set("uLampFaceAlpha", b.settings->transparentBackground ? 1.0f : 0.0f);
  p.set("uCoverageFrame", b.coverageFrame);
  p.set("uCoverageStream", 0);
  p.bind("uProbeAtlas", dummy_);  // (an inactive volume binds none)
  if (b.probes) b.probes->bind(p);
  // Not while a program writes the cache (its writers do not declare the sampler either).
  if (readsProbeCache(b)) p.bind("uProbeCache", b.targets->probeCache);
}

// The batch's shadow-map slots: each area sample's, and the punctual samples' that have one.
void LightingPass::setShadowSlots(const gl::Program& p, const LightingBatch& b) {
  std::vector<glm::mat4> shadowMatrices(kMaxShadowMaps, glm::mat4(1.0f));
  std::vector<glm::vec4> shadowParams(kMaxShadowMaps, glm::vec4(0.0f));
  for (const PunctualDraw& pd : b.punctual) {
    if (pd.shadowSlot < 0) continue;
    shadowMatrices[static_cast<size_t>(pd.shadowSlot)] = pd.view.matrix;
    shadowParams[static_cast<size_t>(pd.shadowSlot)] = pd.view.params;
  }
  for (size_t i = 0; i < b.area.size() && i < static_cast<size_t>(kMaxShadowMaps); ++i) {
    if (!b.area[i].shadowed) continue;
    shadowMatrices[i] = b.area[i].view.matrix;
    shadowParams[i] = b.area[i].view.params;
  }
  p.set("uShadowMatrix", std::span<const glm::mat4>(shadowMatrices));
  p.set("uShadowParams", std::span<const glm::vec4>(shadowParams));
}

void LightingPass::setAreaUniforms(const gl::Program& p, const LightingBatch& b) {
  // This batch's area-light samples.
  std::vector<glm::vec3> pos, dir, right, up, radiance;
  std::vector<glm::vec4> shape;
  for (size_t i = 0; i < b.area.size(); ++i) {
    const AreaSampleDraw& a = b.area[i];
    const Light& l = *a.light;
    pos.push_back(l.position);
    dir.push_back(l.direction);
    right.push_back(l.right);
    up.push_back(l.up);
    shape.emplace_back(l.width, l.height, static_cast<float>(lightKind(l.type).shaderCode),
                       a.shadowed ? static_cast<float>(i) : -1.0f);
    radiance.push_back(l.color * l.intensity * a.weight);
  }
  p.set("uAreaPos", std::span<const glm::vec3>(pos));
  p.set("uAreaDir", std::span<const glm::vec3>(dir));
  p.set("uAreaRight", std::span<const glm::vec3>(right));
  p.set("uAreaUp", std::span<const glm::vec3>(up));
  p.set("uAreaShape", std::span<const glm::vec4>(shape));
  p.set("uAreaRadiance", std::span<const glm::vec3>(radiance));
  if (readsLightCache(b)) {
    std::vector<int> layers;
    for (const AreaSampleDraw& a : b.area) layers.push_back(lightCacheLayer(b, a.lightIndex));
    p.bind("uLightCache", b.targets->lightCache);
    p.set("uAreaLayer", std::span<const int>(layers));
  }
}

void LightingPass::setPunctualUniforms(const gl::Program& p, const LightingBatch& b) {
  // Punctual lights (first batch only; past kMaxPunctualLights they are not shaded).
  std::vector<glm::vec4> ppos, pdir;
  std::vector<glm::vec3> pcol;
  std::vector<glm::vec2> cone;
  std::vector<int> punctualShadow;
  std::vector<glm::vec4> disk;
  std::vector<glm::vec4> pointPos(kMaxPointShadows, glm::vec4(0.0f));
  std::vector<glm::vec4> pointParams(kMaxPointShadows, glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
  for (const PunctualDraw& pd : b.punctual) {
    if (static_cast<int>(ppos.size()) >= kMaxPunctualLights) break;
    const Light& l = *pd.light;
    const PunctualSample sample = sampleOf(pd, *b.settings);
    ppos.emplace_back(l.position, static_cast<float>(sample));
    pdir.emplace_back(pd.direction, l.range);
    disk.emplace_back(l.direction, sample == PunctualSample::Sun ? directionalDisk(l, *b.settings)
                                                                  : 0.0f);
    // The shadow: a point sample's cube map, any other's 2D map (-1: unshadowed).
    if (sample == PunctualSample::Point) {
      punctualShadow.push_back(pd.pointShadow);
      if (pd.pointShadow >= 0) {
        pointPos[static_cast<size_t>(pd.pointShadow)] = pd.pointView.position;
        pointParams[static_cast<size_t>(pd.pointShadow)] = pd.pointView.params;
      }
    } else {
      punctualShadow.push_back(pd.shadowSlot);
    }
    pcol.push_back(l.color * l.intensity * pd.weight);
    const float cosOuter = std::cos(l.outerConeAngle), cosInner = std::cos(l.innerConeAngle);
    const float scale = 1.0f / std::max(cosInner - cosOuter, 1e-4f);
    cone.push_back(sample == PunctualSample::Spot ? glm::vec2(scale, -cosOuter * scale)
                                                  : glm::vec2(0.0f));
  }
  p.set("uPunctualPos", std::span<const glm::vec4>(ppos));
  p.set("uPunctualDir", std::span<const glm::vec4>(pdir));
  p.set("uPunctualColor", std::span<const glm::vec3>(pcol));
  p.set("uPunctualCone", std::span<const glm::vec2>(cone));
  p.set("uPunctualShadow", std::span<const int>(punctualShadow));
  p.set("uPunctualDisk", std::span<const glm::vec4>(disk));
  p.set("uPointShadowPos", std::span<const glm::vec4>(pointPos));
  p.set("uPointShadowParams", std::span<const glm::vec4>(pointParams));
}

// The environment behind the scene: drawn after the opaque geometry at the far plane, so only
// uncovered pixels pay for it. `alpha` is 1, or a probe capture's distance for the sky.
Status LightingPass::drawBackground(const LightingBatch& b, const GpuEnvironment& shown,
                                    const glm::mat3& envRotation, const CameraMatrices& camera,
                                    float blur, float alpha) {
  const int accumulate = b.accumulateFrame > 0 ? 1 : 0, blurred = blur > 0.0f ? 1 : 0;
  auto& slot = backgrounds_[static_cast<size_t>(accumulate * 2 + blurred)];
  if (!slot) {
    auto made = FullscreenPass::create(
        *library_, "background.frag", /*farPlane=*/true,
        {{"PN_ACCUMULATE", std::to_string(accumulate)}, {"PN_BLUR", std::to_string(blurred)}});
    if (!made) return made.error();
    slot.emplace(std::move(*made));
  }
  const FullscreenPass& pass = *slot;
  const gl::Program& bg = pass.begin(/*depthTest=*/true);
  shown.bind(bg, b.settings->environmentIntensity, envRotation);
  bg.set("uInvViewProj", glm::inverse(camera.projection * camera.view));
  bg.set("uBackgroundBlur", blur);
  bg.set("uBackgroundAlpha", alpha);
  if (b.accumulateFrame > 0) {
    // Where no background is shown the sample is the clear colour: (0, 0, 0, 1), or
    // (0, 0, 0, 0) with a transparent background (`alpha` 0).
    bg.set("uBackgroundScale", backgroundShown(b) ? 1.0f : 0.0f);
    setAccumulation(bg, b);
  }
  pass.draw();
  return {};
}

Status LightingPass::drawBackground(const LightingBatch& b, const glm::mat3& envRotation) {
  // Accumulating, the pixels the scene leaves are drawn whether or not a background is shown.
  if (backgroundShown(b) || b.accumulateFrame > 0) {
    return drawBackground(b, b.background ? *b.background : *b.environment, envRotation,
                          *b.camera, b.settings->backgroundBlur,
                          b.settings->transparentBackground ? 0.0f : 1.0f);
  }
  return {};
}

void LightingPass::setAccumulation(const gl::Program& p, const LightingBatch& b) {
  p.bind("uPrevious", b.targets->accumulation[static_cast<size_t>(b.targets->current)].color);
  p.set("uWeight", 1.0f / static_cast<float>(b.accumulateFrame));
}

Status LightingPass::drawCapture(const LightingBatch& b, const std::vector<CaptureView>& views,
                                 float skyDistance) {
  if (!b.scene || views.empty()) return {};
  const glm::mat3 envRotation = environmentLookup(*b.settings);
  LightingVariant pass = variant(b, false, !b.area.empty(), !b.punctual.empty());
  pass.capture = 1;
  gl::PipelineState state;
  if (!b.first) {
    state.depthTest = gl::DepthTest::LessEqual;
    state.depthWrite = false;
    state.blend = gl::Blend::Additive;
  }
  // All faces in one instanced draw per item over the whole strip (mesh.vert), then the sky
  // face by face, wherever the probe sees no geometry (whether or not the view shows it).
  PN_CHECK(views.size() == 6, "a capture has six faces");
  std::vector<glm::mat4> faceViewProj;
  for (const CaptureView& view : views) {
    PN_CHECK(view.x == static_cast<int>(faceViewProj.size()) * view.size && view.y == 0 &&
                 view.size == views.front().size,
             "capture faces are squares side by side");
    faceViewProj.push_back(view.camera.projection * view.camera.view);
  }
  const int faceSize = views.front().size;
  gl::setViewport(0, 0, 6 * faceSize, faceSize);
  const auto setup = [&](const gl::Program& p) {
    setUniforms(p, b, envRotation);
    p.set("uFaceViewProj", std::span<const glm::mat4>(faceViewProj));
    p.set("uCaptureFaceSize", faceSize);
    p.set("uViewOrigin", views.front().camera.viewOrigin);
  };
  PN_TRY(drawByMaterial(pass, *b.scene, b.scene->opaque(), state, setup, 6));
  if (b.coverageFrame >= 0)
    PN_TRY(drawByMaterial(pass, *b.scene, b.scene->blended(), state, setup, 6));
  if (b.first) {
    for (const CaptureView& view : views) {
      gl::setViewport(view.x, view.y, view.size, view.size);
      PN_TRY(drawBackground(b, *b.environment, envRotation, view.camera, 0.0f, skyDistance));
    }
  }
  return {};
}

// The frame's depth: a depth-only pass of the same geometry (same vertex shader, invariant
// positions, the same MASK and coverage decisions), so that the lighting draws with LEQUAL shade
// each pixel once however much geometry overlaps it. Overdraw cost llvmpipe a third of the
// kitchen's lighting pass and a sixth of the Cornell box's.
void LightingPass::drawDepth(const LightingBatch& b) {
  const gl::Program& dp = *depthOnly_;
  dp.use();
  dp.set("uViewProj", b.camera->projection * b.camera->view);
  dp.set("uView", b.camera->view);
  dp.set("uCoverageFrame", b.coverageFrame);
  dp.set("uCoverageStream", 0);
  drawItems(dp, *b.scene, b.scene->opaque(), true, {.colorWrite = false});
  if (b.coverageFrame >= 0)
    drawItems(dp, *b.scene, b.scene->blended(), true, {.colorWrite = false});
}

// The probe volume's lookups for this view, where this frame's depth pass left the surfaces.
Status LightingPass::writeProbeCache(const LightingBatch& b, const glm::mat3& envRotation) {
  PN_TRY(b.targets->ensureProbeCache());
  b.targets->probeCacheFramebuffer.bind();
  gl::apply({.depthWrite = false});  // the depth pass left colour writes off
  gl::clearBufferFloat(0, 0, 0, 0, 0);
  gl::clearBufferFloat(1, 0, 0, 0, 0);
  gl::clearBufferFloat(2, 0, 0, 0, 0);
  LightingBatch writing = b;
  writing.readProbeCache = false;  // the targets being written are not sampled
  writing.accumulateFrame = 0;
  const auto setupCache = [&](const gl::Program& p) { setUniforms(p, writing, envRotation); };
  LightingVariant cachePass = variant(writing, false, false, false);
  cachePass.probeCacheWrite = 1;
  gl::PipelineState cacheState;
  cacheState.depthTest = gl::DepthTest::LessEqual;
  cacheState.depthWrite = false;
  PN_TRY(drawByMaterial(cachePass, *b.scene, b.scene->opaque(), cacheState, setupCache));
  if (b.coverageFrame >= 0) {
    PN_TRY(drawByMaterial(cachePass, *b.scene, b.scene->blended(), cacheState, setupCache));
  }
  return {};
}

// The lights' unshadowed shading where this frame's depth pass left the surfaces, a layer a
// light, added with the batch's weight (the mean over the view's first frames).
Status LightingPass::writeLightCache(const LightingBatch& b, const glm::mat3& envRotation) {
  const int layers = static_cast<int>(b.cachedLights.size());
  PN_TRY(b.targets->ensureLightCache(layers));
  b.targets->lightCacheFramebuffer.bind();
  if (b.clearLightCache) {
    gl::apply({.depthWrite = false});
    for (int i = 0; i < layers; ++i) gl::clearBufferFloat(i, 0, 0, 0, 0);
  }
  LightingBatch writing = b;
  writing.readLightCache = false;
  writing.accumulateFrame = 0;
  writing.area = b.cachedLights;
  writing.punctual.clear();
  gl::PipelineState cacheState;
  cacheState.depthTest = gl::DepthTest::LessEqual;
  cacheState.depthWrite = false;
  cacheState.blend = gl::Blend::Additive;
  const auto setupCache = [&](const gl::Program& p) {
    setUniforms(p, writing, envRotation);
    p.set("uLightCacheWeight", b.lightCacheWeight);
  };
  LightingVariant cachePass = variant(writing, false, true, false);
  cachePass.lightCacheWrite = static_cast<uint32_t>(layers);
  return drawByMaterial(cachePass, *b.scene, b.scene->opaque(), cacheState, setupCache);
}

// BLEND surfaces without stochastic coverage: alpha-blended back to front over the frame.
Status LightingPass::drawBlendedSorted(const LightingBatch& b, const LightingVariant& pass,
                                       const std::function<void(const gl::Program&)>& setup) {
  const CameraMatrices& cm = *b.camera;
  std::vector<DrawItem> sorted = b.scene->blended();
  std::sort(sorted.begin(), sorted.end(), [&](const DrawItem& x, const DrawItem& y) {
    // Back to front: by distance from the eye, or along the parallel rays (orthographic).
    auto far = [&](const glm::vec3& c) {
      return cm.viewOrigin.w > 0.5f ? glm::distance(c, cm.position)
                                    : -glm::dot(c, glm::vec3(cm.viewOrigin));
    };
    return far(x.center) > far(y.center);
  });
  // (The background pass left its own program bound: setup makes each current again.)
  return drawByMaterial(pass, *b.scene, sorted, {.depthWrite = false, .blend = gl::Blend::Alpha},
                        setup);
}

// Transmissive surfaces' own light, batch by batch, beside the frame (which keeps showing what
// is behind them until composeTransmission). Every layer in front of the opaque scene adds its
// light: a back wall seen through a front one.
Status LightingPass::drawTransmissiveOwn(const LightingBatch& b, const glm::mat3& envRotation) {
  PN_TRY(b.targets->ensureTransmission());
  b.targets->glassLight.framebuffer.bind();
  if (b.first) {
    gl::apply({});
    gl::clearBufferFloat(0, 0, 0, 0, 0);
  }
  LightingBatch glass = b;
  glass.readProbeCache = false;  // the caches hold what lies behind
  glass.readLightCache = false;
  gl::PipelineState own;
  own.depthTest = gl::DepthTest::LessEqual;
  own.depthWrite = false;
  own.blend = gl::Blend::Additive;
  LightingVariant glassPass = variant(glass, b.occlusion, !b.area.empty(), !b.punctual.empty());
  glassPass.transmission = 1;
  PN_TRY(drawByMaterial(glassPass, *b.scene, b.scene->transmissive(), own,
                        [&](const gl::Program& p) { setUniforms(p, glass, envRotation); }));
  b.targets->frame.framebuffer.bind();
  return {};
}

Status LightingPass::draw(const LightingBatch& b) {
  PN_CHECK(b.accumulateFrame == 0 ||
               (b.first && b.accumulateFrame > 1 && (!b.scene || b.scene->transmissive().empty())),
           "LightingPass: only a whole frame's only batch accumulates as it draws");
  const glm::mat3 envRotation = environmentLookup(*b.settings);
  // Where the frame's sample goes: the frame target, or the mean being made.
  const gl::Framebuffer& out =
      b.accumulateFrame > 0
          ? b.targets->accumulation[static_cast<size_t>(1 - b.targets->current)].framebuffer
          : b.targets->frame.framebuffer;
  out.bind();
  const glm::ivec2 drawn = drawnSize(b);
  gl::setViewport(0, 0, drawn.x, drawn.y);
  if (b.first) {
    gl::apply({});
    // A reduced frame clears only its part (unsplit: no band's scissor is on).
    const bool part = drawn != glm::ivec2(b.targets->width, b.targets->height);
    if (part) gl::setScissor(0, 0, drawn.x, drawn.y);
    // (Accumulating, every pixel is drawn: by the scene or by the background.) Alpha is
    // coverage with a transparent background.
    if (b.accumulateFrame == 0) {
      gl::clearBufferFloat(0, 0, 0, 0, b.settings->transparentBackground ? 0.0f : 1.0f);
    }
    gl::clearDepth(1.0f);
    if (part) gl::disableScissor();
  }
  if (!b.scene) {
    if (b.first) PN_TRY(drawBackground(b, envRotation));
    return {};
  }
  if (b.first) drawDepth(b);
  if (b.writeProbeCache && b.probes) {
    PN_TRY(writeProbeCache(b, envRotation));
    out.bind();
  }
  if (b.writeLightCache && !b.cachedLights.empty()) {
    PN_TRY(writeLightCache(b, envRotation));
    out.bind();
  }
  const LightingVariant pass = variant(b, b.occlusion, !b.area.empty(), !b.punctual.empty());
  const auto setup = [&](const gl::Program& p) { setUniforms(p, b, envRotation); };
  gl::PipelineState opaque;
  opaque.depthTest = gl::DepthTest::LessEqual;
  opaque.depthWrite = false;
  if (!b.first) opaque.blend = gl::Blend::Additive;
  PN_TRY(drawByMaterial(pass, *b.scene, b.scene->opaque(), opaque, setup));
  // Stochastic coverage: BLEND surfaces are drawn like opaque ones, minus the fragments this
  // frame does not keep, in every batch (the same decisions each time).
  if (b.coverageFrame >= 0)
    PN_TRY(drawByMaterial(pass, *b.scene, b.scene->blended(), opaque, setup));
  if (b.first) PN_TRY(drawBackground(b, envRotation));
  if (b.first && b.settings->shadowIntensity > 0.0f) PN_TRY(drawGround(b, envRotation));
  if (b.first && b.coverageFrame < 0 && !b.scene->blended().empty()) {
    PN_TRY(drawBlendedSorted(b, pass, setup));
  }
  if (!b.scene->transmissive().empty()) PN_TRY(drawTransmissiveOwn(b, envRotation));
  return {};
}

Status LightingPass::copyBehind(const LightingBatch& b) {
  if (!b.scene || b.scene->transmissive().empty()) return {};
  RenderTargets& t = *b.targets;
  PN_TRY(t.ensureTransmission());
  t.frame.framebuffer.blitColorTo(t.behind.framebuffer, t.width, t.height);
  return {};
}

Status LightingPass::composeTransmission(const LightingBatch& b) {
  if (!b.scene || b.scene->transmissive().empty() || !b.targets->glassLight.color) return {};
  RenderTargets& t = *b.targets;
  t.frame.framebuffer.bind();
  const glm::ivec2 drawn = drawnSize(b);
  gl::setViewport(0, 0, drawn.x, drawn.y);
  LightingBatch compose = b;
  compose.readProbeCache = false;
  const glm::mat3 envRotation = environmentLookup(*b.settings);
  // The nearest transmissive layer replaces the pixel: its own light (all layers') plus what
  // it transmits of the copy.
  gl::PipelineState state;
  state.depthTest = gl::DepthTest::LessEqual;
  LightingVariant composing = variant(compose, b.occlusion, false, false);
  composing.transmission = 2;
  return drawByMaterial(composing, *b.scene, b.scene->transmissive(), state,
                        [&](const gl::Program& p) {
                          setUniforms(p, compose, envRotation);
                          // After setUniforms, which binds the probe cache's units (shared).
                          p.bind("uBehind", t.behind.color);
                          p.bind("uGlassLight", t.glassLight.color);
                          p.set("uBehindDepthValid", b.occlusion ? 1 : 0);
                        });
}

}  // namespace penumbra::passes
