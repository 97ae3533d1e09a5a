#include "progressive/probe_relocation.h"

#include <algorithm>
#include <cmath>

namespace penumbra::progressive {

glm::vec3 relocateProbe(std::span<const ProbeSight> sights, glm::vec3 offset, glm::vec3 spacing) {
  const float clearance = kProbeClearance * std::min(spacing.x, std::min(spacing.y, spacing.z));
  float total = 0.0f, back = 0.0f;
  const ProbeSight* nearestBack = nullptr;
  const ProbeSight* nearestFront = nullptr;
  for (const ProbeSight& s : sights) {
    total += s.solidAngle;
    if (!std::isfinite(s.distance)) continue;
    if (s.backface) {
      back += s.solidAngle;
      if (!nearestBack || s.distance < nearestBack->distance) nearestBack = &s;
    } else if (!nearestFront || s.distance < nearestFront->distance) {
      nearestFront = &s;
    }
  }
  glm::vec3 next = offset;
  if (nearestBack && back > kProbeBuriedShare * total) {
    next = offset + nearestBack->direction * (nearestBack->distance + clearance);
  } else if (nearestFront && nearestFront->distance < 0.5f * clearance) {
    next = offset - nearestFront->direction * (clearance - nearestFront->distance);
  } else {
    return offset;
  }
  const glm::vec3 limit = kProbeMaxOffset * spacing;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(next[a]) > limit[a]) return offset;
  }
  return next;
}

}  // namespace penumbra::progressive
