#include "progressive/sequences.h"

#include <algorithm>
#include <cmath>

namespace penumbra::progressive {

float radicalInverse(uint32_t index, uint32_t base) {
  double inv = 1.0 / base, f = inv, r = 0.0;
  for (uint32_t i = index; i > 0; i /= base) {
    r += f * (i % base);
    f *= inv;
  }
  return static_cast<float>(std::min(r, 0.99999994));
}

glm::vec2 r2(uint32_t index) {
  // 1/g and 1/g^2 for the plastic number g = 1.3247179572447...
  const double a1 = 0.7548776662466927, a2 = 0.5698402909980532;
  double x = 0.5 + a1 * index, y = 0.5 + a2 * index;
  return {static_cast<float>(x - std::floor(x)), static_cast<float>(y - std::floor(y))};
}

glm::vec2 seedOffset(uint32_t seed, uint32_t stream) {
  if (seed == 0) return {0.0f, 0.0f};
  // PCG-style integer hash: a fixed function of (seed, stream).
  auto hash = [](uint32_t v) {
    v = v * 747796405u + 2891336453u;
    uint32_t w = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    return (w >> 22u) ^ w;
  };
  uint32_t a = hash(seed * 0x9E3779B9u + stream);
  uint32_t b = hash(a ^ 0x85EBCA6Bu);
  return {static_cast<float>(a >> 8) / 16777216.0f, static_cast<float>(b >> 8) / 16777216.0f};
}

glm::vec2 jitter(int frame, uint32_t seed) {
  if (frame <= 1) return {0.0f, 0.0f};
  // A Kronecker sequence, not Halton (2, 3): a light's samples land on every k-th frame (k = 8
  // for 64 samples over 512 frames), and every k-th Halton point of base 2 lies in one k-th of
  // the pixel, which moved that light's shading off the pixel centre (0.31 px at 512 frames: an
  // embossed outline against the environment term, 2.8 8-bit steps RMS on a textured model).
  // Every arithmetic subsequence of a Kronecker sequence is again one, so any stride averages
  // to the pixel centre. The step is (1/g, 1/g^3) for g the real root of x^4 = x + 1 (Roberts'
  // R3 constants), the pair that stratified as well as Halton at every stride tried, and
  // rationally independent of the occlusion's R2 and the sky's Halton (5, 7).
  const double a1 = 0.8191725133961645, a3 = 0.5497004779019703;
  const double k = static_cast<double>(frame - 1);
  const glm::vec2 o = seedOffset(seed, 1);
  double x = 0.5 + a1 * k + o.x, y = 0.5 + a3 * k + o.y;
  return {static_cast<float>(x - std::floor(x)) - 0.5f,
          static_cast<float>(y - std::floor(y)) - 0.5f};
}

glm::vec2 concentricDisk(glm::vec2 u) {
  glm::vec2 o = u * 2.0f - 1.0f;
  if (o.x == 0.0f && o.y == 0.0f) return {0.0f, 0.0f};
  const float pi4 = 0.785398163f;
  float r, theta;
  if (std::abs(o.x) > std::abs(o.y)) {
    r = o.x;
    theta = pi4 * (o.y / o.x);
  } else {
    r = o.y;
    theta = 2.0f * pi4 - pi4 * (o.x / o.y);
  }
  return {r * std::cos(theta), r * std::sin(theta)};
}

std::vector<glm::vec2> lightSamplePoints(int n, LightShape shape, float aspect, uint32_t seed) {
  std::vector<glm::vec2> pts;
  if (n <= 0) return pts;
  if (n == 1 || shape == LightShape::Point) {
    pts.assign(static_cast<size_t>(n), glm::vec2(0.5f));
    return pts;
  }
  glm::vec2 rot = seedOffset(seed, 2);
  pts.reserve(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    glm::vec2 p((i + 0.5f) / n, radicalInverse(static_cast<uint32_t>(i), 2));
    p += rot;
    p -= glm::floor(p);
    pts.push_back(p);
  }
  sortFromCentre(pts, shape, aspect);
  return pts;
}

void sortFromCentre(std::vector<glm::vec2>& pts, LightShape shape, float aspect) {
  auto key = [&](glm::vec2 p) {
    if (shape == LightShape::Disk) return glm::length(concentricDisk(p));
    glm::vec2 d = (p - 0.5f) * glm::vec2(aspect, 1.0f);
    return glm::length(d);
  };
  std::stable_sort(pts.begin(), pts.end(),
                   [&](glm::vec2 a, glm::vec2 b) { return key(a) < key(b); });
}

glm::vec2 lightSequencePoint(uint32_t index, LightShape shape, uint32_t seed) {
  if (shape == LightShape::Point) return glm::vec2(0.5f);
  const glm::vec2 p = r2(index) + seedOffset(seed, 2);
  return p - glm::floor(p);
}

}  // namespace penumbra::progressive
