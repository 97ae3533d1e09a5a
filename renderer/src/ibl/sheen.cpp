// The sheen lobe of KHR_materials_sheen and its directional-albedo table. Charlie's
// distribution is broad and peaks at grazing half vectors, so cosine-distributed light
// directions integrate it well (no importance sampling of D needed).
#include <algorithm>
#include <cmath>

#include "ibl/parallel.h"
#include "ibl/sampling.h"
#include "penumbra/ibl.h"

namespace penumbra::ibl {

namespace {

// Estevez & Kulla 2017, eq. (3): a fit of ln Lambda for alpha = 0 and 1, blended by (1 - a)^2.
float lambdaFit(float x, float alpha) {
  const float t = (1.0f - alpha) * (1.0f - alpha);
  const float a = 21.5473f + (25.3245f - 21.5473f) * t;
  const float b = 3.82987f + (3.32435f - 3.82987f) * t;
  const float c = 0.19823f + (0.16801f - 0.19823f) * t;
  const float d = -1.97760f + (-1.27393f + 1.97760f) * t;
  const float e = -4.32054f + (-4.85967f + 4.32054f) * t;
  return a / (1.0f + b * std::pow(x, c)) + d * x + e;
}

// Lambda(cos theta), with the fit mirrored above 1/2 for a smooth, symmetric terminator.
float sheenLambda(float cosTheta, float alpha) {
  return cosTheta < 0.5f
             ? std::exp(lambdaFit(cosTheta, alpha))
             : std::exp(2.0f * lambdaFit(0.5f, alpha) - lambdaFit(1.0f - cosTheta, alpha));
}

}  // namespace

float sheenAlpha(float perceptualRoughness) {
  const float r = std::clamp(perceptualRoughness, 0.07f, 1.0f);
  return r * r;
}

float sheenD(float nDotH, float alpha) {
  const float sin2 = std::max(1.0f - nDotH * nDotH, 0.0f);
  const float inv = 1.0f / alpha;
  return (2.0f + inv) * std::pow(sin2, 0.5f * inv) / (2.0f * kPi);
}

float sheenV(float nDotV, float nDotL, float alpha) {
  const float nv = std::max(nDotV, 1e-4f), nl = std::max(nDotL, 1e-4f);
  const float v =
      1.0f / ((1.0f + sheenLambda(nv, alpha) + sheenLambda(nl, alpha)) * 4.0f * nv * nl);
  return std::clamp(v, 0.0f, 1.0f);
}

float integrateSheenAlbedo(float nDotV, float perceptualRoughness, int samples) {
  PN_CHECK(samples > 0, "samples must be positive");
  const float alpha = sheenAlpha(perceptualRoughness);
  const float nv = std::clamp(nDotV, 1e-4f, 1.0f);
  const glm::vec3 v(std::sqrt(1.0f - nv * nv), 0.0f, nv);
  double sum = 0.0;
  for (int i = 0; i < samples; ++i) {
    const glm::vec2 u = hammersley(static_cast<uint32_t>(i), static_cast<uint32_t>(samples));
    // Cosine-distributed l: pdf = n.l / pi, so f n.l / pdf = pi D V.
    const float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
    const glm::vec3 l(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(1.0f - u.x, 0.0f)));
    if (l.z <= 0.0f) continue;
    const glm::vec3 h = glm::normalize(v + l);
    sum += kPi * sheenD(h.z, alpha) * sheenV(nv, l.z, alpha);
  }
  return static_cast<float>(std::min(sum / samples, 1.0));
}

Image computeSheenLut(int size, int samples, int threads) {
  PN_CHECK(size > 0 && samples > 0, "LUT size and samples must be positive");
  Image lut(size, size, 1);
  parallelFor(size, threads, [&](int y) {
    const float roughness = (static_cast<float>(y) + 0.5f) / static_cast<float>(size);
    for (int x = 0; x < size; ++x) {
      const float nv = (static_cast<float>(x) + 0.5f) / static_cast<float>(size);
      lut.pixel(x, y)[0] = integrateSheenAlbedo(nv, roughness, samples);
    }
  });
  return lut;
}

}  // namespace penumbra::ibl
