// SkyDistribution: luminance-proportional directions over the environment for sky shadows.
// Texels are picked by their share of luminance x solid angle, then a point is placed
// uniformly in the texel's face coordinates; the pdf accounts for the face's own distortion
// (d omega = 4 ds dt / (1 + x^2 + y^2)^(3/2)), so estimates built on it are unbiased.
#include <algorithm>
#include <cmath>

#include "penumbra/ibl.h"

namespace penumbra::ibl {

namespace {

float luminance(const glm::vec3& c) {
  return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

// (1 + x^2 + y^2)^(3/2) / 4 at face coordinates s, t: solid-angle density -> (s, t) density.
float faceJacobian(float s, float t) {
  const float x = 2.0f * s - 1.0f, y = 2.0f * t - 1.0f;
  const float r2 = 1.0f + x * x + y * y;
  return r2 * std::sqrt(r2) * 0.25f;
}

}  // namespace

SkyDistribution SkyDistribution::build(const Cubemap& cube, int resolution, bool upperOnly) {
  PN_CHECK(cube.mipCount() > 0 && cube.size > 0, "sky distribution of an empty cube map");
  SkyDistribution d;
  const int n = std::clamp(resolution, 1, cube.size);
  const int block = cube.size / n;
  d.resolution_ = n;
  const std::vector<double> omega = texelSolidAngles(n);
  d.radiance_.resize(static_cast<size_t>(kFaceCount) * n * n);
  d.solidAngle_.resize(d.radiance_.size());
  d.cdf_.resize(d.radiance_.size());
  double sum = 0.0;
  for (int f = 0; f < kFaceCount; ++f) {
    const Image& face = cube.face(0, f);
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        glm::dvec3 c(0.0);
        for (int by = 0; by < block; ++by) {
          for (int bx = 0; bx < block; ++bx) {
            const float* p = face.pixel(x * block + bx, y * block + by);
            c += glm::dvec3(p[0], p[1], p[2]);
          }
        }
        const size_t i = (static_cast<size_t>(f) * n + y) * n + x;
        d.radiance_[i] = glm::vec3(c / static_cast<double>(block * block));
        d.solidAngle_[i] = static_cast<float>(omega[static_cast<size_t>(y) * n + x]);
        if (upperOnly && texelDirection(f, x, y, n).y <= 0.0f) d.radiance_[i] = glm::vec3(0.0f);
        const float l = luminance(d.radiance_[i]);
        sum += std::isfinite(l) && l > 0.0f ? static_cast<double>(l) * d.solidAngle_[i] : 0.0;
        d.cdf_[i] = sum;
      }
    }
  }
  d.total_ = sum;
  return d;
}

SkySample SkyDistribution::sample(glm::vec2 u) const {
  PN_CHECK(!empty(), "sampling an empty sky");
  const double target = std::clamp(static_cast<double>(u.x), 0.0, 1.0) * total_;
  const size_t i = static_cast<size_t>(
      std::min<std::ptrdiff_t>(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin(),
                               static_cast<std::ptrdiff_t>(cdf_.size()) - 1));
  // The residual of u.x within the texel's CDF interval is uniform: reuse it for the position.
  const double lo = i == 0 ? 0.0 : cdf_[i - 1];
  const double width = cdf_[i] - lo;
  const float ux =
      width > 0.0 ? static_cast<float>(std::clamp((target - lo) / width, 0.0, 1.0)) : 0.5f;
  const int n = resolution_;
  const int face = static_cast<int>(i / (static_cast<size_t>(n) * n));
  const int y = static_cast<int>((i / n) % n), x = static_cast<int>(i % n);
  const float s = (static_cast<float>(x) + ux) / static_cast<float>(n);
  const float t = (static_cast<float>(y) + std::clamp(u.y, 0.0f, 1.0f)) / static_cast<float>(n);
  SkySample out;
  out.direction = cubeDirection(face, s, t);
  out.radiance = radiance_[i];
  const double p = luminance(radiance_[i]) * solidAngle_[i] / total_;  // probability of texel i
  out.pdf = static_cast<float>(p * n * n * faceJacobian(s, t));
  return out;
}

float SkyDistribution::pdf(const glm::vec3& direction) const {
  if (empty()) return 0.0f;
  const CubeCoord c = cubeCoord(direction);
  const int n = resolution_;
  const int x = std::min(static_cast<int>(c.s * n), n - 1);
  const int y = std::min(static_cast<int>(c.t * n), n - 1);
  const size_t i = (static_cast<size_t>(c.face) * n + y) * n + x;
  const float l = luminance(radiance_[i]);
  if (!(l > 0.0f)) return 0.0f;
  const double p = l * solidAngle_[i] / total_;
  return static_cast<float>(p * n * n * faceJacobian(c.s, c.t));
}

}  // namespace penumbra::ibl
