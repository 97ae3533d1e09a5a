// LightingPass: the forward shading of one intermediate frame (lighting.frag) and the
// environment behind the scene (background.frag). One draw of the scene per batch of up to
// kMaxShadowMaps area-light samples: the first batch adds the environment (with this frame's
// occlusion rays), punctual lights, emission and the background, and alpha-blends BLEND
// surfaces in frame 1; later batches add their light on top. Program variants (PN_OCCLUSION,
// PN_AREA, PN_PUNCTUAL) keep frame 1 a plain forward pass, and each is specialised on the
// features of the material it draws (built on first use).
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <map>
#include <vector>

#include <glm/glm.hpp>

#include "gl/program.h"
#include "gl/texture.h"
#include "gpu/gpu_environment.h"
#include "gpu/gpu_scene.h"
#include "passes/camera_math.h"
#include "passes/fullscreen_pass.h"
#include "passes/lighting_variant.h"
#include "passes/point_shadow_pass.h"
#include "passes/shadow_pass.h"
#include "passes/targets.h"
#include "penumbra/frame_plan.h"
#include "penumbra/settings.h"

namespace penumbra::passes {

class ProbeVolume;

// One area-light sample of the batch (sorted by light), with its shadow map if it has one.
struct AreaSampleDraw {
  const Light* light = nullptr;
  int lightIndex = 0;
  float weight = 1.0f;  // the distributor's m / n_i
  bool shadowed = false;
  ShadowView view;  // its map is slot i of the ShadowPass
};

struct PunctualDraw {
  const Light* light = nullptr;
  float weight = 1.0f;
  glm::vec3 direction{0.0f};  // of travel, this sample's (directional lights are jittered)
  int shadowSlot = -1;        // its shadow map in the ShadowPass, or -1: unshadowed
  ShadowView view;
  int pointShadow = -1;  // point lights: its cube map in the PointShadowPass, or -1
  PointShadowView pointView;
  // A sky-shadow sample (render::skyLight): shades (visibility - 1) x its light on the diffuse
  // term only, where this frame's diffuse occlusion ray did not already replace the
  // environment's light.
  bool skyLoss = false;
};

// The rotation that turns a world direction into the environment's (its uEnvRotation).
glm::mat3 environmentLookup(const RenderSettings& s);

struct LightingBatch {
  RenderTargets* targets = nullptr;
  // The part of the targets drawn, from their bottom-left corner: all of it (0: the targets'
  // size), or a reduced frame 1 (ProgressiveSettings::previewScale).
  int drawWidth = 0, drawHeight = 0;
  const GpuScene* scene = nullptr;  // may be null: background only
  const GpuEnvironment* environment = nullptr;
  // The view's background (Renderer::setSkybox: model-viewer's skybox-image); null: the
  // environment. It lights nothing: probe captures see the environment.
  const GpuEnvironment* background = nullptr;
  const ShadowPass* shadows = nullptr;
  const PointShadowPass* pointShadows = nullptr;
  const RenderSettings* settings = nullptr;
  const CameraMatrices* camera = nullptr;  // jittered
  glm::vec2 sequence{0.0f};                // the frame's low-discrepancy point
  float occlusionDistance = 1.0f;          // in effect (the automatic one resolved)
  bool first = true;       // clears the frame and adds environment, punctual lights, background
  bool occlusion = false;  // the prepass is valid: occlusion rays and screen-space indirect light
  int coverageFrame = -1;  // stochastic coverage index of BLEND surfaces (< 0: alpha-blend)
  std::vector<AreaSampleDraw> area;
  std::vector<PunctualDraw> punctual;
  // The probe volume (null or inactive: diffuse environment light as before).
  const ProbeVolume* probes = nullptr;
  // The per-view cache of the volume's lookups (targets->probeCache; first batch with
  // occlusion only): remake it before shading, and read it.
  bool writeProbeCache = false;
  bool readProbeCache = false;
  // The area lights' per-view cache (targets->lightCache; first batch only): the lights it
  // holds (layer i: cachedLights[i], weight 1, unshadowed), whether this frame adds its
  // unshadowed shading to it (times lightCacheWeight; clearing it first with clearLightCache),
  // and whether the batch's samples read it instead of evaluating their lights.
  std::vector<AreaSampleDraw> cachedLights;
  bool writeLightCache = false;
  bool clearLightCache = false;
  float lightCacheWeight = 0.0f;
  bool readLightCache = false;
  // The frame's only batch, with nothing drawn over it later (no transmissive surfaces), may
  // add its sample straight to the running mean: frame n (> 1) is drawn, background included,
  // into the accumulation target that is not current, as mean_{n-1} + (x_n - mean_{n-1}) / n.
  // The frame target is neither cleared nor written, and no accumulate pass runs.
  int accumulateFrame = 0;  // n, or 0: draw into the frame target
};

// One face of a probe capture: its camera and its square in the bound capture target.
struct CaptureView {
  CameraMatrices camera;
  int x = 0, y = 0, size = 0;
};

class LightingPass {
 public:
  static Result<LightingPass> create(gl::ShaderLibrary& library);
  Status draw(const LightingBatch& batch);
  // Draws a batch into the bound framebuffer for the six faces of a probe capture (squares
  // side by side from x = 0, one instanced draw per item) with the PN_CAPTURE variant: both
  // faces of every surface, and where no geometry is, the environment with alpha
  // `skyDistance` (first batch). Extra batches add their light.
  Status drawCapture(const LightingBatch& batch, const std::vector<CaptureView>& views,
                     float skyDistance);
  // After a frame's last batch: copies the whole frame (the scene behind transmissive
  // surfaces), then draws those surfaces over it, each showing its own light (drawn with every
  // batch) plus what it transmits of the copy (transmission_compose.frag). Uses the
  // first batch's camera and prepass. No-ops without transmissive surfaces.
  Status copyBehind(const LightingBatch& batch);
  Status composeTransmission(const LightingBatch& batch);
  // Whether batch b's area-light samples read the area lights' cache: every sample's light is
  // in it, and no point light's cube map takes its unit.
  static bool readsLightCache(const LightingBatch& b);

 private:
  // The cache layer of scene light `lightIndex` in batch b (-1: not cached).
  static int lightCacheLayer(const LightingBatch& b, int lightIndex);
  // Whether batch b reads its probe volume's per-view cache (it has been made).
  static bool readsProbeCache(const LightingBatch& b);
  // The kinds of punctual samples in a batch (a bit per PunctualSample, scene/light_kinds.h): only their
  // code is compiled.
  static uint32_t punctualKinds(const LightingBatch& b);
  // The kind of sample a punctual draw is (scene/light_kinds.h).
  static PunctualSample sampleOf(const PunctualDraw& d, const RenderSettings& s);
  // The batch's sample counts, and where its area samples' light changes, into v: the
  // shader's loops over samples then run to a constant and unroll, so every uniform array is
  // read at a constant index (llvmpipe reads one at a loop counter lane by lane). A plan has a
  // few counts per batch, so a few more programs.
  static void setSampleCounts(LightingVariant& v, const LightingBatch& b);
  // The variant of batch b's own probe state and the given terms.
  static LightingVariant variant(const LightingBatch& b, bool occlusion, bool area, bool punctual);
  // The program of a variant (LightingVariant::fragmentFile) and a material's features
  // (ProgramKey), built on first use.
  Result<gl::Program*> program(LightingVariant v, const MaterialFeatures& features);
  // The running mean's inputs of a batch that accumulates as it draws (accumulateFrame).
  static void setAccumulation(const gl::Program& p, const LightingBatch& b);
  // Draws items, each with the program of its pass and material; `setup` makes a program
  // current and sets the batch's uniforms on it the first time this call uses it. With
  // `instances` > 0 both faces of every item are drawn that many times (probe captures).
  Status drawByMaterial(const LightingVariant& v, const GpuScene& scene,
                        const std::vector<DrawItem>& items, gl::PipelineState state,
                        const std::function<void(const gl::Program&)>& setup, int instances = 0);
  void setUniforms(const gl::Program& p, const LightingBatch& b, const glm::mat3& envRotation);
  // setUniforms' parts: the view's, the shadow-map slots, each light kind's samples.
  void setViewUniforms(const gl::Program& p, const LightingBatch& b, const glm::mat3& envRotation);
  static void setShadowSlots(const gl::Program& p, const LightingBatch& b);
  void setAreaUniforms(const gl::Program& p, const LightingBatch& b);
  static void setPunctualUniforms(const gl::Program& p, const LightingBatch& b);
  // The parts of draw(): the depth-only pass, the per-view caches' writes, the sorted BLEND
  // surfaces and the transmissive surfaces' own light.
  void drawDepth(const LightingBatch& b);
  Status writeProbeCache(const LightingBatch& b, const glm::mat3& envRotation);
  Status writeLightCache(const LightingBatch& b, const glm::mat3& envRotation);
  Status drawBlendedSorted(const LightingBatch& b, const LightingVariant& v,
                           const std::function<void(const gl::Program&)>& setup);
  Status drawTransmissiveOwn(const LightingBatch& b, const glm::mat3& envRotation);
  Status drawBackground(const LightingBatch& b, const glm::mat3& envRotation);
  // The shadow-catching ground over the first batch's background (passes/ground_shadow.cpp).
  Status drawGround(const LightingBatch& b, const glm::mat3& envRotation);
  Status drawBackground(const LightingBatch& b, const GpuEnvironment& shown,
                        const glm::mat3& envRotation, const CameraMatrices& camera, float blur,
                        float alpha);

  gl::ShaderLibrary* library_ = nullptr;
  std::map<std::array<uint64_t, 2>, gl::Program*> programs_;  // by ProgramKey::key()
  gl::Program* depthOnly_ = nullptr;
  // The background's programs: [PN_ACCUMULATE * 2 + PN_BLUR]; the blurred ones made on first
  // use (a blur is a setting few views have).
  std::array<std::optional<FullscreenPass>, 4> backgrounds_;
  gl::Texture2D dummy_;  // bound in place of the prepass when there is none
  std::map<std::array<uint64_t, 2>, gl::Program*> groundPrograms_;  // by ProgramKey::key()
  gl::VertexArray groundVao_;  // attribute-less: ground.vert makes the corners
};

}  // namespace penumbra::passes
