#include "progressive/first_light.h"

#include <algorithm>
#include <cmath>

namespace penumbra::progressive {

float environmentShare(const std::vector<Light>& lights, float environmentMeanRadiance,
                       const Bounds& bounds) {
  constexpr float kPi = 3.14159265f;
  const float env = kPi * std::max(environmentMeanRadiance, 0.0f);
  const bool sized = bounds.valid() && bounds.radius() > 0.0f && std::isfinite(bounds.radius());
  float own = 0.0f;
  for (const Light& l : lights) {
    const float power =
        std::max(l.color.r, std::max(l.color.g, l.color.b)) * std::max(l.intensity, 0.0f);
    if (l.type == LightType::Directional) {
      own += power;
      continue;
    }
    // Without bounds (no geometry) every light counts fully: there is nothing to light anyway.
    const float r = sized ? std::max(bounds.radius(), glm::length(l.position - bounds.center()))
                          : 1.0f;
    own += l.isArea() ? std::min(power * l.area() / (r * r), kPi * power) : power / (r * r);
  }
  if (!std::isfinite(own)) return 0.0f;
  if (own <= 0.0f) return 1.0f;
  return std::isfinite(env) ? env / (env + own) : 1.0f;
}

}  // namespace penumbra::progressive
