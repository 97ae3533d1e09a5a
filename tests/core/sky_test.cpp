// SkyDistribution (sky shadows): its pdf integrates to 1, sample() and pdf() agree, and the
// estimator the renderer builds on it, L cos / pdf, averages to the cosine-weighted integral
// of the environment (so the light it subtracts under a shadow is right on average).
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "penumbra/ibl.h"

namespace penumbra::ibl {
namespace {

// A sky brighter towards +Y with a warm patch near +X, over a dark ground.
Cubemap testSky(int size) {
  Cubemap cube(size, 1);
  for (int f = 0; f < kFaceCount; ++f) {
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const glm::vec3 d = texelDirection(f, x, y, size);
        glm::vec3 c = d.y > 0.0f ? glm::vec3(0.3f, 0.5f, 1.0f) * (0.5f + d.y) : glm::vec3(0.05f);
        if (glm::dot(d, glm::normalize(glm::vec3(1, 0.3f, 0))) > 0.95f) c += glm::vec3(4, 3, 1);
        float* p = cube.face(0, f).pixel(x, y);
        p[0] = c.r, p[1] = c.g, p[2] = c.b;
      }
    }
  }
  return cube;
}

TEST(SkyDistributionTest, PdfIntegratesToOne) {
  const SkyDistribution sky = SkyDistribution::build(testSky(64), 16);
  ASSERT_FALSE(sky.empty());
  const int n = 128;
  const std::vector<double> omega = texelSolidAngles(n);
  double sum = 0.0;
  for (int f = 0; f < kFaceCount; ++f) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        sum += sky.pdf(texelDirection(f, x, y, n)) * omega[static_cast<size_t>(y) * n + x];
      }
    }
  }
  EXPECT_NEAR(sum, 1.0, 2e-3);
}

TEST(SkyDistributionTest, SampleAndPdfAgree) {
  const SkyDistribution sky = SkyDistribution::build(testSky(64), 16);
  for (int i = 0; i < 500; ++i) {
    const glm::vec2 u((i + 0.5f) / 500.0f, std::fmod(i * 0.618034f, 1.0f));
    const SkySample s = sky.sample(u);
    EXPECT_NEAR(glm::length(s.direction), 1.0f, 1e-5f);
    EXPECT_NEAR(s.pdf, sky.pdf(s.direction), 1e-3f * s.pdf) << i;
  }
}

TEST(SkyDistributionTest, CosineWeightedEstimateMatchesTheIntegral) {
  const SkyDistribution sky = SkyDistribution::build(testSky(64), 16);
  // Reference: the sky itself, integrated on a fine grid (the distribution's 16-texel
  // averages differ from it only within each texel, which the tolerance allows for).
  const int n = 128;
  const std::vector<double> omega = texelSolidAngles(n);
  const Cubemap fine = testSky(64);
  for (const glm::vec3 normal :
       {glm::vec3(0, 1, 0), glm::normalize(glm::vec3(1, 0.2f, 0.3f)), glm::vec3(0, -1, 0)}) {
    glm::dvec3 reference(0.0);
    for (int f = 0; f < kFaceCount; ++f) {
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          const glm::vec3 d = texelDirection(f, x, y, n);
          const float c = glm::dot(d, normal);
          if (c <= 0.0f) continue;
          reference += glm::dvec3(sampleCubemap(fine, 0, d)) *
                       (static_cast<double>(c) * omega[static_cast<size_t>(y) * n + x]);
        }
      }
    }
    glm::dvec3 estimate(0.0);
    const int samples = 200000;
    for (int i = 0; i < samples; ++i) {
      const glm::vec2 u((i + 0.5f) / samples, std::fmod(i * 0.7548777f, 1.0f));
      const SkySample s = sky.sample(u);
      const float c = glm::dot(s.direction, normal);
      if (c > 0.0f) estimate += glm::dvec3(s.radiance) * static_cast<double>(c / s.pdf);
    }
    estimate /= samples;
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(estimate[k], reference[k], 0.03 * reference[k] + 1e-3) << "channel " << k;
    }
  }
}

TEST(SkyDistributionTest, BlackEnvironmentIsEmpty) {
  EXPECT_TRUE(SkyDistribution::build(Cubemap(16, 1), 8).empty());
}

}  // namespace
}  // namespace penumbra::ibl
