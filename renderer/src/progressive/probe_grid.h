// ProbeGrid: where the irradiance probes of the probe volume sit and in which order they are
// captured. A regular grid over the scene's bounds (or the scene file's override), the outer
// probes a tenth of a spacing inside the bounds (kProbeClearance), so none sits on a bounding
// wall and none far from it; each probe may then move within its cell (progressive/
// probe_relocation.h, done on the GPU side). Its spacing follows the bounds, so a model
// in millimetres and a room in metres get the same layout. Plain data and pure functions: the
// GPU side (passes/probe_volume) only reads it.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/scene.h"

namespace penumbra::progressive {

// At most this many probes (an atlas of 64 x 64 tiles of 16 texels fits WebGL2's 4096 limit).
inline constexpr int kMaxProbes = 4096;

struct ProbeGrid {
  glm::vec3 origin{0.0f};   // centre of probe (0, 0, 0)
  glm::vec3 spacing{1.0f};  // between neighbours along each axis (> 0 even with one probe)
  glm::ivec3 counts{0};     // probes along x, y, z
  float diagonal = 1.0f;    // of the volume's box: distances in the probe maps are in this unit
  int count() const { return counts.x * counts.y * counts.z; }
  bool empty() const { return count() == 0; }
  glm::ivec3 cell(int index) const;
  glm::vec3 position(int index) const;
  // Atlas layout: probe i is tile (i % columns, i / columns).
  int columns() const;
  int rows() const;
};

// The grid for a scene box: `density` probes along the box's longest side (at least one along
// every axis, about as many per unit length on the others; an axis under an eighth of a cell
// thick gets two layers, half a cell outside its faces); `counts` > 0 on an axis overrides it.
// Empty for an invalid box.
ProbeGrid placeProbes(const Bounds& box, float density, glm::ivec3 counts = glm::ivec3(0));

// The probes the volume's capture number `capture` updates, `perCapture` of them: consecutive
// runs of a fixed permutation of all probes (a stride coprime with the count, so successive
// captures spread over the volume instead of sweeping it plane by plane). Every probe is
// captured once per count / perCapture captures.
std::vector<int> probesForCapture(const ProbeGrid& grid, uint64_t capture, int perCapture);

// Mean captures a probe below which the volume is filling (it captures faster, and its per-view
// cache is remade more often), and from which it has settled (it captures fewer).
inline constexpr double kProbeSettledCaptures = 4.0;

// How many probes frame `frame` (1-based) captures, for `perFrame` (the setting) and the
// volume's mean captures a probe: until it has settled (four), a sweep every kProbeFillFrames
// frames, at most kProbeFillCaptures a frame, so a small or middling volume settles within
// about 16 frames. The image is the mean of every frame, so each frame shaded by a volume
// still filling leaves its deficit in the mean as a bias that falls only as 1/N: on the milk
// truck, filling in 32 frames instead left 0.96 steps RMS at 64 frames against 0.82 (the same
// captures, earlier). A settled volume takes half the setting, as its running means then move
// by a few percent a sweep, less than the frame's own noise, and no more than a sweep per 32
// frames (a small volume would otherwise recapture each probe every few frames, each capture
// drawing the whole scene six times): a fractional rate spread evenly over the frames. Never
// more than `count`.
inline constexpr int kProbeFillFrames = 4;
inline constexpr int kProbeFillCaptures = 16;
int probeCapturesThisFrame(int perFrame, int count, double meanCaptures, int frame);

// Whether a still view's frame remakes the per-view cache of the volume's lookups, given the
// frames since the last remake (< 0: none this view) and the mean captures a probe now: every
// other frame while the volume is filling (a longer lag would show in the early images), then
// every kProbeCacheInterval frames. Each remake is drawn at one frame's sub-pixel jitter and one
// state of the volume, and the image's probe light is the mean of the remakes it saw: remade
// ever more rarely (when the captures had grown by a quarter, about ten times in 1024 frames),
// DamagedHelmet's image converged on a stale remake for dozens of frames, and its stopping oracle
// was 176 frames instead of 91 (docs/decisions/2026-12-07-probe-cache-remakes.md).
inline constexpr int kProbeCacheInterval = 8;
bool remakeProbeCache(int framesSince, double meanCaptures);

}  // namespace penumbra::progressive
