// Renderer: Penumbra's progressive renderer. Give it a scene, an environment, a camera and
// settings; each step() draws and accumulates one cheap intermediate frame chosen by the
// progressive controller (frame 1: environment only, plus each light from its centre where the
// scene's own lights carry it; depth/normal prepass at frame 2; area lights with one shadow map
// per light sample from frame floor(m f_d)), until frame m or, for an automatic view, until its
// image is measured converged (convergence()).
// readRadiance() gives the linear running mean, readDisplay() the exposed, tone-mapped image.
// Needs a current GL context (GlContext::create) for its whole life.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "penumbra/animation.h"
#include "penumbra/environment_format.h"
#include "penumbra/error.h"
#include "penumbra/frame_plan.h"
#include "penumbra/image.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"

namespace penumbra {

struct RendererOptions {
  bool desktopGl = false;       // GlContext::isDesktopGl()
  bool forceHalfFloat = false;  // accumulate in RGBA16F even where RGBA32F is renderable
  // Waits for the GPU after every pass and records its time in FrameStats (benchmarks only:
  // it serialises CPU and GPU work).
  bool profilePasses = false;
  // For a host's context (GlContext::adoptCurrent): every call that touches GL saves the GL
  // state it changes and restores it before returning (docs/embedding.md lists what is kept).
  bool preserveHostState = false;
  // Caches the probe volume's per-pixel lookups for a still view, remade every few frames once
  // the volume has filled (off: every frame looks the probes up; for A/B runs and tests).
  bool probeCache = true;
  // Caches the area lights' unshadowed shading for a still view (the mean over its first
  // jittered frames); later frames only test each light sample's shadow map (off: every frame
  // evaluates the lights; for A/B runs and tests).
  bool lightCache = true;
  // Diffuse occlusion rays at a quarter of the pixels, each 2x2 block tracing one (off: every
  // pixel traces its own; for A/B runs and tests).
  bool quarterOcclusion = true;
  // A frame drawn in one lighting pass (no second batch of area lights, no transmissive
  // surfaces) adds its sample to the running mean as it draws, instead of in an accumulation
  // pass of its own (off: always the separate pass; for A/B runs and tests).
  bool fusedAccumulation = true;
  // With BLEND surfaces (stochastic transparency from frame 2), the displayed image of frames
  // 2-16 mixes the alpha-blended frame 1 back in, fading to the mean, so that the next few
  // frames' binary coverage does not break it into specks (off: the mean as it is; for A/B
  // runs and tests). The mean, the convergence measure and readRadiance are never mixed.
  bool firstFrameHold = true;
};

// Punctual (KHR_lights_punctual) lights shaded per frame; further ones are not (RenderJob
// warns).
inline constexpr int kMaxPunctualLights = 8;

// The most bands Renderer::setFrameTiles() splits a frame into.
inline constexpr int kMaxFrameTiles = 64;

// What Renderer::stepPart() did: the frame it worked on (0 once converged), whether that frame
// is now complete (accumulated, in readRadiance() and present()), and which part of how many
// it was (1-based).
struct FramePart {
  int frame = 0;
  bool done = true;
  int part = 0, parts = 0;
};

// Where present() draws the displayed image: a framebuffer (0 = the default one, or a host's
// framebuffer object by its GL name) and a viewport in it.
struct PresentTarget {
  uint32_t framebuffer = 0;
  int x = 0, y = 0, width = 0, height = 0;
};

// What the last frame did, for tests, benchmarks and progress displays.
struct FrameStats {
  int frame = 0;
  int shadowPasses = 0;
  int lightingPasses = 0;
  bool prepass = false;
  bool occlusion = false;
  // Milliseconds per pass, filled only with RendererOptions::profilePasses.
  double prepassMs = 0, shadowMs = 0, lightingMs = 0, accumulateMs = 0;
  double occlusionMs = 0;          // the diffuse occlusion rays (a quarter-resolution pass)
  int probeCaptures = 0;           // probes of the probe volume captured in this frame
  double probeMs = 0;              // their time (with profilePasses)
  bool probeCacheWritten = false;  // the per-view cache of the volume's lookups was remade
  bool probeLookups = false;       // the lighting read the probe volume (not while it is empty)
  bool lightCacheWritten = false;  // the area lights' per-view cache took this frame's shading
  bool lightCacheRead = false;     // this frame's area-light samples read that cache
  bool fusedAccumulation = false;  // the lighting pass added the sample to the mean (no pass)
};

// How far a view is from done. An automatic view (ProgressiveSettings::frames 0) measures its
// displayed image at checkpoints (frames 2, 4, 6, 8, then about 2^(1/4) apart;
// docs/architecture.md, "First light and measured convergence") and stops when its displayed
// image's error against the image at maxFrames, estimated per 8x8 tile from its change since the
// checkpoint at about half the frames, is under convergenceThreshold 8-bit steps (RMS) and that
// of 99 % of its tiles under three times that.
struct ConvergenceInfo {
  bool automatic = false;       // frames is auto
  bool measured = false;        // a checkpoint after the first has been measured in this view
  bool converged = false;       // the last measurement met the criterion
  int frame = 0;                // the last measured checkpoint
  double error = 0.0;           // its RMS change over the image (8-bit steps): the estimated error
  double tileError = 0.0;       // its 99th-percentile tile change (RMS, 8-bit steps)
  double convergedTiles = 0.0;  // the fraction of tiles under three times the threshold
  // The frame by which the view is expected to be done: m; for an automatic view from the
  // error's measured fall (decay), a checkpoint, at most maxFrames (its frame once converged).
  int expectedFrames = 0;
  // The fraction of tiles no longer shaded (adaptive frames, skipConvergedTiles).
  double skippedTiles = 0.0;
  // The error falls as N^-decay, measured between checkpoints (1/2 for noise, up to 1).
  double decay = 0.5;
};

// The probe volume as laid out for the current scene (probes 0: off or unavailable).
struct ProbeVolumeInfo {
  int probes = 0;
  int counts[3] = {0, 0, 0};
  int64_t bytes = 0;          // GPU memory: atlases, capture target, light maps
  double meanCaptures = 0.0;  // captures per probe so far
  int moved = 0;              // probes relocation moved off their grid points (so far)
};

class Renderer {
 public:
  static Result<std::unique_ptr<Renderer>> create(const RendererOptions& options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  Status setScene(const Scene& scene);
  // KHR_materials_variants: shows variant `index` of the scene's Scene::variants (-1: the
  // primitives' own materials, as after setScene). Restarts accumulation; the geometry stays on
  // the GPU, and so does the probe volume's layout (its light is gathered again).
  Status setVariant(int index);
  Status setEnvironment(const PackedEnvironment& environment);
  // The background shown behind the scene apart from the environment that lights it
  // (model-viewer's skybox-image), with the environment's intensity and rotation; null: the
  // environment itself again. It lights nothing. Restarts accumulation.
  Status setSkybox(const PackedEnvironment* skybox);
  void setCamera(const Camera& camera);
  // Playback: poses a scene loaded with LoadOptions::playback at `time` seconds of animation
  // `animation` (an index into Scene::animations; -1: the rest pose) on the GPU, its morph
  // targets and skins once per pose (passes/deform_pass.h), and starts the view over: a playing
  // animation shows each pose's first frame, a pose held converges as any still does. Lights
  // and cameras keep their places.
  Status setPose(int animation, float time);
  // A blend of poses (animation.h's PoseLayer: a crossfade from one animation to the next).
  Status setPose(std::span<const PoseLayer> layers);
  Status setSettings(const RenderSettings& settings);

  // Draws the next intermediate frame (the rest of it when stepPart() began it); returns its
  // number, or 0 once frame m is done.
  Result<int> step();
  // Draws one part of the next intermediate frame, so a host with a time budget per display
  // frame (the web viewer) never waits for a whole frame. Unsplit (frameTiles 1) a part is
  // the whole frame. Split into k tiles, each pass over the image (prepass, every lighting
  // batch, the accumulation) draws one of k horizontal bands per part and each shadow map is
  // a part of its own. The image is the same as unsplit, and until the last part the
  // displayed and read images are the previous complete frame's. Any restart drops a frame in
  // progress.
  Result<FramePart> stepPart();
  // A preview of the current view for a host whose view is moving: frame 1 (environment light)
  // drawn at settings().progressive.previewScale of the resolution (a quarter of the pixels at
  // 0.5) and upsampled into the image, which the display and read-backs then show. It is not
  // part of the mean: accumulation starts over, and the next step() draws frame 1 at full
  // resolution, the same frame 1 as without a preview.
  Status preview();
  // The number of bands of frames that stepPart() begins from now on (1..kMaxFrameTiles, and
  // at most the image height); a frame in progress keeps its own.
  void setFrameTiles(int tiles);
  int frameTiles() const;
  // Restarts accumulation at frame 1 and empties the probe volume: frame n after restart() is
  // frame n of a fresh renderer. Changes restart accumulation by themselves; a camera change
  // keeps the probe volume, which does not depend on the view.
  void restart();
  // Frame m is done, or an automatic view measured itself converged or reached maxFrames.
  bool converged() const;
  int framesDone() const;
  // m, or an automatic view's cap (maxFrames).
  int totalFrames() const;
  ConvergenceInfo convergence() const;
  const FrameStats& lastFrame() const;
  ProbeVolumeInfo probeVolumeInfo() const;

  // The running mean of linear radiance (before exposure), RGBA float, row 0 at the top.
  Result<Image> readRadiance();
  // The displayed image: exposure, tone mapping and sRGB applied, RGBA in [0, 1]
  // (toneMap() followed by a read-back).
  Result<Image> readDisplay();
  // Applies exposure and tone mapping to the running mean, into an internal 8-bit image.
  Status toneMap();
  // Waits until the GL has finished all submitted work (benchmarks time whole frames).
  void finish();
  // Draws the displayed image (the same exposure, tone-mapping and sRGB pass as readDisplay)
  // into the default framebuffer — the browser canvas — over a canvasWidth x canvasHeight
  // viewport, scaling the accumulated image when the render resolution differs (nearest).
  // Leaves framebuffer 0 bound. The web viewer calls it once per animation frame.
  Status present(int canvasWidth, int canvasHeight);
  // The same into any framebuffer and viewport (a host's render target).
  Status present(const PresentTarget& target);

  // The accumulation format in use and the capability report, for logs.
  std::string capabilityReport() const;
  // The device's largest texture side: textures larger than this must be downscaled on load
  // (JobRequest::maxTextureSize).
  int maxTextureSize() const;
  const RenderSettings& settings() const;
  // The GPU memory held by the textures, renderbuffers and buffers of every renderer in this
  // process, from their sizes and formats (mip levels and layers included; what a driver pads
  // is not). Frame targets and shadow maps are made by the first frame that needs them, so a
  // renderer whose settings changed several times before it drew holds only the last size.
  static int64_t gpuMemoryBytes();

 private:
  Renderer();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace penumbra
