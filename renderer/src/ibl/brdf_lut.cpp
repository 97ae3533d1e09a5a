// DFG lookup table for the split sum with height-correlated Smith GGX, integrated with
// visible-normal sampling (Heitz 2018): its weight G2 / G1 is bounded, so 512 samples per texel
// converge far better than sampling D alone, even at grazing angles.
#include <algorithm>
#include <cmath>

#include "ibl/parallel.h"
#include "ibl/sampling.h"
#include "penumbra/ibl.h"

namespace penumbra::ibl {

namespace {

// The Hammersley points in polar form, shared by every texel of the table.
struct PolarPoints {
  std::vector<float> r, cosPhi, sinPhi;
  explicit PolarPoints(int samples) : r(samples), cosPhi(samples), sinPhi(samples) {
    for (int i = 0; i < samples; ++i) {
      const glm::vec2 u = hammersley(i, samples);
      r[i] = std::sqrt(u.x);
      cosPhi[i] = std::cos(2.0f * kPi * u.y);
      sinPhi[i] = std::sin(2.0f * kPi * u.y);
    }
  }
};

glm::vec3 integrate(float nDotV, float perceptualRoughness, const PolarPoints& points) {
  const float alpha = std::max(perceptualRoughness * perceptualRoughness, 1e-4f);
  const float nv = std::clamp(nDotV, 1e-4f, 1.0f);
  const glm::vec3 v(std::sqrt(1.0f - nv * nv), 0.0f, nv);
  const float g1v = smithG1(nv, alpha);
  const int samples = static_cast<int>(points.r.size());
  double a = 0.0;
  double b = 0.0;
  for (int i = 0; i < samples; ++i) {
    const glm::vec3 h =
        sampleGgxVndfPolar(v, points.r[i], points.cosPhi[i], points.sinPhi[i], alpha);
    const float vh = glm::dot(v, h);
    const float nl = 2.0f * vh * h.z - v.z;  // (reflect(v, h)).z
    if (nl <= 0.0f || vh <= 0.0f) continue;
    // f cos / pdf = (D G2 / (4 nv nl)) nl / (G1(v) D / (4 nv)) = G2 / G1(v).
    const float weight = smithG2(nv, nl, alpha) / g1v;
    const float x = 1.0f - vh;
    const float x2 = x * x;
    const float fc = x2 * x2 * x;
    a += (1.0f - fc) * weight;
    b += fc * weight;
  }
  a /= samples;
  b /= samples;
  return {static_cast<float>(a), static_cast<float>(b), static_cast<float>(a + b)};
}

}  // namespace

glm::vec3 integrateDfg(float nDotV, float perceptualRoughness, int samples) {
  PN_CHECK(samples > 0, "samples must be positive");
  return integrate(nDotV, perceptualRoughness, PolarPoints(samples));
}

Image computeBrdfLut(const BrdfLutOptions& options) {
  PN_CHECK(options.size > 0 && options.samples > 0, "LUT size and samples must be positive");
  const int n = options.size;
  Image lut(n, n, 3);
  const PolarPoints points(options.samples);
  parallelFor(n, options.threads, [&](int y) {
    const float roughness = (static_cast<float>(y) + 0.5f) / static_cast<float>(n);
    for (int x = 0; x < n; ++x) {
      const float nv = (static_cast<float>(x) + 0.5f) / static_cast<float>(n);
      const glm::vec3 dfg = integrate(nv, roughness, points);
      float* p = lut.pixel(x, y);
      p[0] = dfg.x;
      p[1] = dfg.y;
      p[2] = dfg.z;
    }
  });
  return lut;
}

}  // namespace penumbra::ibl
