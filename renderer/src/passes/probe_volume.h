// ProbeVolume: world-space, multi-bounce indirect light that fills frame by frame (issue 14).
// Irradiance probes on a progressive::ProbeGrid over the scene; each capture renders one
// probe's cube map (PN_CAPTURE lighting: every light at full weight, shadowed by maps the
// volume keeps one per light and re-renders from a new point on the light one per capture, the
// environment where the probe sees sky, and what the volume already holds on every surface, so
// repeated captures add bounces), and projects them onto octahedral tiles of three maps:
// irradiance, the mean and mean square distance for Chebyshev visibility, and the radiance the
// probe sees (glossy reflections of the room where it sees geometry rather than sky). The three
// share one atlas texture (one texture unit, one framebuffer), laid out by atlasLayout(). Each tile
// keeps a running mean of its captures (constant-alpha blending in place, the weight 1/n capped so
// the newest bounces keep coming in). A probe's first capture also places it: one buried in
// geometry or at a wall's nose moves within its cell and is captured again
// (progressive/probe_relocation.h). The volume does not depend on the view: camera moves keep it.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "gl/objects.h"
#include "gl/program.h"
#include "gl/texture.h"
#include "passes/lighting_pass.h"
#include "passes/point_shadow_pass.h"
#include "passes/shadow_pass.h"
#include "progressive/probe_grid.h"

namespace penumbra::passes {

// A light as a capture shades it: at full weight, its map rendered from `origin` (area lights:
// a point on the surface) or along `direction` (spot: its own; directional: jittered over its
// angular size), both for ProbeVolume::lightPoint().
struct CaptureLight {
  const Light* light = nullptr;
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f};
};

// What a capture shades with: the scene's lights (and the environment's sun), the point-light
// cube maps the frame uses, the settings and the targets (for LightingPass's bindings).
// Where the three maps sit in the atlas: for `columns` x `rows` probes, the radiance tiles at
// the origin, the depth tiles to their right, the irradiance tiles above those (so 4096 probes
// fit in 2048 texels, WebGL2's guaranteed size), and above all of them one texel a probe with
// its relocation offset (in units of the grid's spacing; every texture unit is taken, so it
// shares the atlas). chunks/probe_volume.glsl computes the same.
struct ProbeAtlasLayout {
  glm::ivec2 size{0};
  glm::ivec2 origin[3];   // irradiance, depth moments, radiance (PN_PROBE_MAP's order)
  int tile[3] = {};       // tile size with its one-texel border
  glm::ivec2 offsets{0};  // probe i's offset at offsets + (i % columns, i / columns)
};
ProbeAtlasLayout atlasLayout(int columns, int rows);

struct ProbeCaptureInputs {
  const GpuScene* scene = nullptr;
  const GpuEnvironment* environment = nullptr;
  std::vector<CaptureLight> lights;
  PointShadowPass* pointShadows = nullptr;
  const RenderSettings* settings = nullptr;
  RenderTargets* targets = nullptr;
  // Re-render one light's map first (round robin; all of them at the first capture). A frame's
  // first capture does; its others reuse the maps: each light map is a full shadow pass, which
  // cost a quarter of a capture, and a probe's mean over frames sees many light points anyway.
  bool newLightMap = true;
};

class ProbeVolume {
 public:
  // Shadowed lights a capture can shade (area, spot, directional; point lights use the frame's
  // cube maps): two shadow passes of kMaxShadowMaps maps.
  static constexpr int kMaxCaptureLights = 2 * kMaxShadowMaps;
  // Captures averaged at most: later ones weigh 1/kHistory (an exponential moving average, as
  // DDGI's hysteresis), so the bounces each capture adds still arrive. 16, not 4: with the
  // per-view cache remade every 8 frames the image follows the volume closely, and its
  // captures' noise (one point on each area light) showed: the kitchen looked done at 401
  // frames with 4, 313 with 16, the room (cm) 667 and 521 (decisions/2026-12-07-probe-cache-remakes.md).
  static constexpr int kHistory = 16;
  // A probe's first kReplaced + 1 captures replace its value instead of joining the mean: while
  // the volume fills they differ by the bounces they saw more than by noise, and a mean would
  // keep the first capture's missing bounces for many sweeps (in the room (cm) the image's mean
  // rose 4.9 % from 64 to 1024 frames with it, 3.5 % without).
  static constexpr int kReplaced = 2;

  static Result<ProbeVolume> create(gl::ShaderLibrary& library);
  // Lays out a grid and empties the volume (an empty grid turns it off); `relocate`: probes move
  // at their first capture (progressive/probe_relocation.h), else they stay on the grid.
  Status reset(const progressive::ProbeGrid& grid, bool relocate = true);
  // Empties the volume, same grid (the lights or the environment changed).
  void clear();
  bool active() const { return !grid_.empty(); }
  const progressive::ProbeGrid& grid() const { return grid_; }
  uint64_t captures() const { return captures_; }
  // The point on each light (in [0, 1]^2) the next capture's re-rendered map uses: the centre
  // first, then the R2 sequence rotated by the seed.
  glm::vec2 lightPoint(uint32_t seed) const;
  // Mean captures per probe so far.
  double meanCaptures() const;
  // Where probe `index` captures from: its grid point moved by relocation (kept across clear():
  // the scene's geometry does not change; a probe moves at its first capture after reset()).
  glm::vec3 probePosition(int index) const;
  // How many probes relocation has moved from their grid points.
  int movedProbes() const;
  // Sets the probe uniforms and binds the atlases on a program in use (none for an inactive
  // volume: the program's PN_PROBES define says whether it looks up).
  void bind(const gl::Program& program) const;
  // Captures the next probe of the grid's order and blends it into the atlases; first
  // re-renders one light's map from lightPoint() if `in.newLightMap`.
  Status capture(LightingPass& lighting, const ProbeCaptureInputs& in);
  // Bytes of GPU memory the volume holds (atlases, capture target, shadow maps).
  int64_t memoryBytes() const;

 private:
  Status ensureCaptureTarget();
  Status renderLightMaps(const ProbeCaptureInputs& in);
  // Renders the six faces of a capture from `position` into the capture target.
  Status drawFaces(LightingPass& lighting, std::vector<LightingBatch>& batches, glm::vec3 position);
  // The offset relocation gives probe `index` from the capture target's distances.
  glm::vec3 relocation(int index) const;
  // Writes probe `index`'s offset into the atlas.
  void writeOffset(int index);

  progressive::ProbeGrid grid_;
  gl::Program* project_ = nullptr;          // irradiance
  gl::Program* projectDepth_ = nullptr;     // depth moments
  gl::Program* projectRadiance_ = nullptr;  // radiance
  gl::VertexArray quad_;
  gl::Texture2D atlas_;
  gl::Framebuffer atlasFb_;
  gl::Texture2D capture_;
  gl::Renderbuffer captureDepth_;
  gl::Framebuffer captureFb_;
  std::vector<ShadowPass> lightMaps_;
  // Per shadowed light: its map's view (after the first capture), and how many it had.
  std::vector<ShadowView> lightViews_;
  std::vector<int> lightIndex_;            // into the light list, per shadowed slot
  std::vector<glm::vec3> lightDirection_;  // of the direction-jittered ones' maps
  bool lightMapsValid_ = false;
  std::vector<int> probeCaptures_;
  std::vector<glm::vec3> offsets_;  // world units, from each probe's grid point
  std::vector<uint8_t> placed_;     // relocation done (a probe's first capture since reset())
  uint64_t captures_ = 0;
  uint64_t lightMapRenders_ = 0;  // re-renders since the first capture (the round robin)
};

}  // namespace penumbra::passes
