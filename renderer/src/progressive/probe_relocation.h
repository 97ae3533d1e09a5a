// Probe relocation: where a probe of the probe volume sits inside its grid cell, so that it sees
// the room rather than the inside of geometry or a wall at its nose (DDGI's relocation,
// Majercik et al., "Scaling Probe-Based Real-Time Dynamic Global Illumination for
// Production", JCGT 2021). Lookups keep the grid's barycentric weights; only where the probe
// looks from moves. Pure: the GPU side (passes/probe_volume) passes what one capture saw.
#pragma once

#include <limits>
#include <span>

#include <glm/glm.hpp>

namespace penumbra::progressive {

// What a probe saw in one direction of its capture.
struct ProbeSight {
  glm::vec3 direction{0.0f, 0.0f, 1.0f};                    // unit
  float distance = std::numeric_limits<float>::infinity();  // to the surface; infinite: sky
  bool backface = false;                                    // the back of a one-sided surface
  float solidAngle = 0.0f;                                  // of the direction's texel
};

// A probe that sees back faces in more than this share of solid angle is buried (inside
// geometry): relocation moves it, and glsl/probe_project.frag marks it unusable while it stays
// (PN_PROBE_BURIED_SHARE, passes/limits.h).
inline constexpr float kProbeBuriedShare = 0.25f;
// The room a probe keeps from what it sees, in units of its smallest spacing: the outer probes
// of a grid sit this far inside the bounds (placeProbes), so a wall on the bounds is not too close.
inline constexpr float kProbeClearance = 0.1f;
// How far a probe may move from its grid point along each axis, in units of that axis' spacing:
// it stays inside its own cell, so the lookups' tetrahedra keep their shape.
inline constexpr float kProbeMaxOffset = 0.45f;

// The next offset (world units, from the probe's grid point) for a probe now at `offset` that
// saw `sights`. Buried: through the nearest back face, kProbeClearance past it. Closer than half
// the clearance to a front face: away from it, to the clearance. A move that would leave the
// probe's cell is not made (the probe stays, and a buried one stays unusable).
glm::vec3 relocateProbe(std::span<const ProbeSight> sights, glm::vec3 offset, glm::vec3 spacing);

}  // namespace penumbra::progressive
