#include "passes/probe_volume.h"

#include <algorithm>
#include <array>

#include <glm/gtc/matrix_transform.hpp>

#include "passes/limits.h"
#include "progressive/probe_relocation.h"
#include "progressive/sequences.h"
#include "scene/light_kinds.h"

namespace penumbra::passes {
namespace {

constexpr int kC = kProbeCaptureSize;
constexpr int kLightMapSize = 512;
// Relocation moves a probe at most this many times, each followed by a fresh capture: a buried
// probe leaves through its nearest back face and may need a second step off the surface.
constexpr int kMaxMoves = 2;
// Cube faces: forward and up of each 90-degree view; right = forward x up (glm::lookAt's).
const std::array<glm::vec3, 6> kForward = {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0),
                                           glm::vec3(0, 1, 0), glm::vec3(0, -1, 0),
                                           glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)};
const std::array<glm::vec3, 6> kUp = {glm::vec3(0, 1, 0),  glm::vec3(0, 1, 0), glm::vec3(0, 0, 1),
                                      glm::vec3(0, 0, -1), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0)};

Result<gl::Texture2D> atlas(int w, int h) {
  return gl::Texture2D::create(
      {.width = w,
       .height = h,
       .format = gl::PixelFormat::RGBA16F,
       .sampler = {.minFilter = gl::Filter::Linear, .magFilter = gl::Filter::Linear}});
}

}  // namespace

ProbeAtlasLayout atlasLayout(int columns, int rows) {
  ProbeAtlasLayout l;
  l.tile[0] = kProbeIrradianceTexels + 2;
  l.tile[1] = kProbeDepthTexels + 2;
  l.tile[2] = kProbeRadianceTexels + 2;
  l.origin[2] = glm::ivec2(0);
  l.origin[1] = glm::ivec2(columns * l.tile[2], 0);
  l.origin[0] = glm::ivec2(columns * l.tile[2], rows * l.tile[1]);
  const int mapsHeight = std::max(rows * l.tile[2], rows * (l.tile[1] + l.tile[0]));
  l.offsets = glm::ivec2(0, mapsHeight);
  l.size = glm::ivec2(columns * (l.tile[2] + std::max(l.tile[0], l.tile[1])), mapsHeight + rows);
  return l;
}

Result<ProbeVolume> ProbeVolume::create(gl::ShaderLibrary& library) {
  ProbeVolume v;
  gl::Program** programs[3] = {&v.project_, &v.projectDepth_, &v.projectRadiance_};
  for (int map = 0; map < 3; ++map) {
    auto p = library.program("fullscreen.vert", "probe_project.frag",
                             {{"PN_FAR_PLANE", "0"}, {"PN_PROBE_MAP", std::to_string(map)}});
    if (!p) return p.error();
    *programs[map] = *p;
  }
  v.quad_ = gl::VertexArray::create();
  for (int i = 0; i < kMaxCaptureLights / kMaxShadowMaps; ++i) {
    auto sp = ShadowPass::create(library, kLightMapSize, true);
    if (!sp) return sp.error();
    v.lightMaps_.push_back(std::move(*sp));
  }
  return v;
}

Status ProbeVolume::reset(const progressive::ProbeGrid& grid, bool relocate) {
  // A grid of the same shape keeps the atlas (a played animation moves the grid every pose).
  const bool sameAtlas = atlas_ && !grid.empty() && grid.columns() == grid_.columns() &&
                         grid.rows() == grid_.rows();
  grid_ = grid;
  if (!sameAtlas) {
    atlas_ = {};
    if (grid_.empty()) return {};
    const ProbeAtlasLayout layout = atlasLayout(grid_.columns(), grid_.rows());
    auto tex = atlas(layout.size.x, layout.size.y);
    if (!tex) return makeError("probe volume: " + tex.message());
    atlas_ = std::move(*tex);
    atlasFb_ = gl::Framebuffer::create();
    atlasFb_.attachColor(0, atlas_);
    atlasFb_.setDrawBuffers(1);
    PN_TRY(atlasFb_.checkComplete());
  }
  offsets_.assign(static_cast<size_t>(grid_.count()), glm::vec3(0.0f));
  placed_.assign(static_cast<size_t>(grid_.count()), relocate ? 0 : 1);
  clear();
  return {};
}

void ProbeVolume::clear() {
  captures_ = 0;
  lightMapRenders_ = 0;
  lightMapsValid_ = false;
  probeCaptures_.assign(static_cast<size_t>(grid_.count()), 0);
  if (grid_.empty()) return;
  gl::apply({.depthTest = gl::DepthTest::Off, .depthWrite = false});
  atlasFb_.bind();
  gl::clearBufferFloat(0, 0, 0, 0, 0);
  for (int i = 0; i < grid_.count(); ++i) {
    if (offsets_[static_cast<size_t>(i)] != glm::vec3(0.0f)) writeOffset(i);
  }
}

glm::vec3 ProbeVolume::probePosition(int index) const {
  return grid_.position(index) + offsets_[static_cast<size_t>(index)];
}

int ProbeVolume::movedProbes() const {
  return static_cast<int>(std::count_if(offsets_.begin(), offsets_.end(),
                                        [](glm::vec3 o) { return o != glm::vec3(0.0f); }));
}

void ProbeVolume::writeOffset(int index) {
  const ProbeAtlasLayout layout = atlasLayout(grid_.columns(), grid_.rows());
  const glm::vec3 o = offsets_[static_cast<size_t>(index)] / grid_.spacing;
  atlasFb_.bind();
  gl::setScissor(layout.offsets.x + index % grid_.columns(),
                 layout.offsets.y + index / grid_.columns(), 1, 1);
  gl::clearBufferFloat(0, o.x, o.y, o.z, 0.0f);
  gl::disableScissor();
}

glm::vec3 ProbeVolume::relocation(int index) const {
  // Alpha: the signed distance in diagonals (negative on a back face), 4 for sky, 0 where
  // nothing was drawn.
  const std::vector<float> texels = captureFb_.readRgbaFloat(0, 0, 0, 6 * kC, kC);
  std::vector<progressive::ProbeSight> sights;
  sights.reserve(static_cast<size_t>(6 * kC * kC));
  for (int f = 0; f < 6; ++f) {
    const glm::vec3 right =
        glm::cross(kForward[static_cast<size_t>(f)], kUp[static_cast<size_t>(f)]);
    for (int y = 0; y < kC; ++y) {
      for (int x = 0; x < kC; ++x) {
        const glm::vec2 st = (glm::vec2(x, y) + 0.5f) * (2.0f / kC) - 1.0f;
        const glm::vec3 d =
            kForward[static_cast<size_t>(f)] + st.x * right + st.y * kUp[static_cast<size_t>(f)];
        const float len = glm::length(d);
        const float a = texels[static_cast<size_t>(4 * (y * 6 * kC + f * kC + x) + 3)];
        progressive::ProbeSight s;
        s.direction = d / len;
        s.solidAngle = 1.0f / (len * len * len);
        s.backface = a < 0.0f;
        if (a != 0.0f && std::abs(a) < 3.5f) s.distance = std::abs(a) * grid_.diagonal;
        sights.push_back(s);
      }
    }
  }
  return progressive::relocateProbe(sights, offsets_[static_cast<size_t>(index)], grid_.spacing);
}

double ProbeVolume::meanCaptures() const {
  if (probeCaptures_.empty()) return 0.0;
  double sum = 0;
  for (int c : probeCaptures_) sum += c;
  return sum / static_cast<double>(probeCaptures_.size());
}

glm::vec2 ProbeVolume::lightPoint(uint32_t seed) const {
  if (captures_ == 0) return glm::vec2(0.5f);
  const glm::vec2 u =
      progressive::r2(static_cast<uint32_t>(captures_)) + progressive::seedOffset(seed, 11);
  return u - glm::floor(u);
}

void ProbeVolume::bind(const gl::Program& p) const {
  if (!active()) return;
  p.bind("uProbeAtlas", atlas_);
  p.set("uProbeOrigin", grid_.origin);
  p.set("uProbeSpacing", grid_.spacing);
  p.set("uProbeCounts", glm::vec3(grid_.counts));
  p.set("uProbeDiagonal", grid_.diagonal);
  p.set("uProbeColumns", grid_.columns());
  p.set("uProbeRows", grid_.rows());
}

// The capture target: one probe's six faces side by side, made on first use.
Status ProbeVolume::ensureCaptureTarget() {
  if (capture_) return {};
  auto tex = atlas(6 * kC, kC);
  if (!tex) return makeError("probe capture target: " + tex.message());
  auto rb = gl::Renderbuffer::create(6 * kC, kC, gl::PixelFormat::Depth24);
  if (!rb) return makeError("probe capture target: " + rb.message());
  capture_ = std::move(*tex);
  captureDepth_ = std::move(*rb);
  captureFb_ = gl::Framebuffer::create();
  captureFb_.attachColor(0, capture_);
  captureFb_.attachDepth(captureDepth_);
  captureFb_.setDrawBuffers(1);
  return captureFb_.checkComplete();
}

// One shadow map per shadowed light (area lights first, then spot and directional ones, so a
// batch's area samples take its lower slots as LightingPass expects): all of them at the first
// capture, then one per `newLightMap` capture from the capture's point on the light, round robin.
Status ProbeVolume::renderLightMaps(const ProbeCaptureInputs& in) {
  if (lightMapsValid_ && !in.newLightMap) return {};
  if (lightMapsValid_) ++lightMapRenders_;  // this re-render's light: 1, 2, ... mod n
  if (!lightMapsValid_) {
    lightIndex_.clear();
    for (const bool area : {true, false}) {
      for (size_t i = 0; i < in.lights.size(); ++i) {
        const Light& l = *in.lights[i].light;
        const bool cube = lightKind(l.type).shadow == ShadowProjection::Cube;
        if (cube || l.isArea() != area) continue;  // cube-mapped lights: below
        if (static_cast<int>(lightIndex_.size()) < kMaxCaptureLights) {
          lightIndex_.push_back(static_cast<int>(i));
        }
      }
    }
    lightViews_.assign(lightIndex_.size(), ShadowView{});
    lightDirection_.assign(lightIndex_.size(), glm::vec3(0.0f));
  }
  const int n = static_cast<int>(lightIndex_.size());
  const int stream = 64;  // coverage stream apart from the frame's maps
  for (int j = 0; j < n; ++j) {
    if (lightMapsValid_ &&
        static_cast<uint64_t>(j) != lightMapRenders_ % static_cast<uint64_t>(n)) {
      continue;
    }
    const CaptureLight& cl = in.lights[static_cast<size_t>(lightIndex_[static_cast<size_t>(j)])];
    const Light& l = *cl.light;
    ShadowPass& pass = lightMaps_[static_cast<size_t>(j / kMaxShadowMaps)];
    const int slot = j % kMaxShadowMaps;
    const int coverage = static_cast<int>(captures_ % 65536);
    lightViews_[static_cast<size_t>(j)] =
        pass.renderLight(slot, *in.scene, l, cl.origin, cl.direction, coverage, stream + j);
    lightDirection_[static_cast<size_t>(j)] = cl.direction;
  }
  lightMapsValid_ = true;
  return {};
}

Status ProbeVolume::capture(LightingPass& lighting, const ProbeCaptureInputs& in) {
  if (!active() || !in.scene) return {};
  const int probe = progressive::probesForCapture(grid_, captures_, 1).front();
  PN_TRY(ensureCaptureTarget());
  PN_TRY(renderLightMaps(in));

  // The lights in batches of one shadow pass each; point lights (their cube maps) and
  // unshadowable extras in the first.
  const int shadowed = static_cast<int>(lightIndex_.size());
  const int batches = std::max(1, (shadowed + kMaxShadowMaps - 1) / kMaxShadowMaps);
  std::vector<LightingBatch> list(static_cast<size_t>(batches));
  for (int b = 0; b < batches; ++b) {
    LightingBatch& batch = list[static_cast<size_t>(b)];
    batch.targets = in.targets;
    batch.scene = in.scene;
    batch.environment = in.environment;
    batch.shadows = &lightMaps_[static_cast<size_t>(b)];
    batch.pointShadows = in.pointShadows;
    batch.settings = in.settings;
    batch.first = b == 0;
    batch.occlusion = false;
    batch.coverageFrame = static_cast<int>(captures_ % 65536);
    batch.probes = this;
  }
  for (int j = 0; j < shadowed; ++j) {
    const auto li = static_cast<size_t>(lightIndex_[static_cast<size_t>(j)]);
    const Light& l = *in.lights[li].light;
    LightingBatch& batch = list[static_cast<size_t>(j / kMaxShadowMaps)];
    if (l.isArea()) {
      batch.area.push_back({.light = &l,
                            .lightIndex = static_cast<int>(li),
                            .weight = 1.0f,
                            .shadowed = true,
                            .view = lightViews_[static_cast<size_t>(j)]});
    } else {
      PunctualDraw pd{&l, 1.0f, lightDirection_[static_cast<size_t>(j)]};
      pd.shadowSlot = j % kMaxShadowMaps;
      pd.view = lightViews_[static_cast<size_t>(j)];
      batch.punctual.push_back(pd);
    }
  }
  int pointMaps = 0;
  for (const CaptureLight& cl : in.lights) {
    if (lightKind(cl.light->type).shadow != ShadowProjection::Cube) continue;
    PunctualDraw pd{cl.light, 1.0f, cl.light->direction};
    if (pointMaps < kMaxPointShadows && in.pointShadows) {
      auto view = in.pointShadows->ensure(pointMaps, *in.scene, cl.light->position);
      if (!view) return view.error();
      pd.pointShadow = pointMaps++;
      pd.pointView = *view;
    }
    if (static_cast<int>(list[0].punctual.size()) < kMaxPunctualLights) {
      list[0].punctual.push_back(pd);
    }
  }

  PN_TRY(drawFaces(lighting, list, probePosition(probe)));
  if (!placed_[static_cast<size_t>(probe)]) {
    // Relocation, once a probe: its first capture shows whether it is buried or at a wall's
    // nose; a moved probe is captured again from where it now sits.
    for (int move = 0; move < kMaxMoves; ++move) {
      const glm::vec3 next = relocation(probe);
      if (next == offsets_[static_cast<size_t>(probe)]) break;
      offsets_[static_cast<size_t>(probe)] = next;
      writeOffset(probe);
      PN_TRY(drawFaces(lighting, list, probePosition(probe)));
    }
    placed_[static_cast<size_t>(probe)] = 1;
  }

  // Project the probe onto its tiles, blended into the running means.
  std::vector<glm::vec3> right(6);
  for (size_t f = 0; f < 6; ++f) right[f] = glm::cross(kForward[f], kUp[f]);
  const ProbeAtlasLayout layout = atlasLayout(grid_.columns(), grid_.rows());
  atlasFb_.bind();
  for (int map = 0; map < 3; ++map) {
    const gl::Program& prog = map == 0 ? *project_ : map == 1 ? *projectDepth_ : *projectRadiance_;
    const int tile = layout.tile[map];
    prog.use();
    prog.bind("uCapture", capture_);
    prog.set("uFaceForward", std::span<const glm::vec3>(kForward));
    prog.set("uFaceRight", std::span<const glm::vec3>(right));
    prog.set("uFaceUp", std::span<const glm::vec3>(kUp));
    const int n = probeCaptures_[static_cast<size_t>(probe)] + 1;
    gl::apply({.depthTest = gl::DepthTest::Off,
               .depthWrite = false,
               .blend = gl::Blend::ConstantMix,
               .cull = gl::Cull::None,
               .blendWeight = 1.0f / static_cast<float>(std::clamp(n - kReplaced, 1, kHistory))});
    const int tx = layout.origin[map].x + (probe % grid_.columns()) * tile;
    const int ty = layout.origin[map].y + (probe / grid_.columns()) * tile;
    gl::setViewport(tx, ty, tile, tile);
    prog.set("uTileOrigin", glm::vec2(tx, ty));
    quad_.draw(gl::Primitive::Triangles, 3);
  }
  ++probeCaptures_[static_cast<size_t>(probe)];
  ++captures_;
  return {};
}

Status ProbeVolume::drawFaces(LightingPass& lighting, std::vector<LightingBatch>& batches,
                              glm::vec3 p) {
  // Six 90-degree views.
  const float diag = grid_.diagonal;
  const glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, 1e-3f * diag, 4.0f * diag);
  std::vector<CaptureView> views;
  for (int f = 0; f < 6; ++f) {
    CaptureView v;
    v.camera.view =
        glm::lookAt(p, p + kForward[static_cast<size_t>(f)], kUp[static_cast<size_t>(f)]);
    v.camera.projection = proj;
    v.camera.position = p;
    v.camera.viewOrigin = glm::vec4(p, 1.0f);
    v.x = f * kC;
    v.size = kC;
    views.push_back(v);
  }
  captureFb_.bind();
  gl::apply({});
  gl::setViewport(0, 0, capture_.width(), capture_.height());
  gl::clearBufferFloat(0, 0, 0, 0, 0);
  gl::clearDepth(1.0f);
  // LightingPass reads the camera for its default uniforms; each view sets its own.
  for (LightingBatch& batch : batches) {
    batch.camera = &views.front().camera;
    PN_TRY(lighting.drawCapture(batch, views, 4.0f));
    batch.camera = nullptr;
  }
  return {};
}

int64_t ProbeVolume::memoryBytes() const {
  int64_t bytes = atlas_.bytes() + capture_.bytes() + captureDepth_.bytes();
  for (const ShadowPass& maps : lightMaps_) bytes += maps.memoryBytes();
  return bytes;
}

}  // namespace penumbra::passes
