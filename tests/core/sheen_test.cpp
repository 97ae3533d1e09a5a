// The sheen lobe (KHR_materials_sheen): Charlie's distribution is a normalised distribution of
// normals, its directional-albedo table matches an independent quadrature, stays within
// [0, 1] and behaves as the lobe should (brighter at grazing angles, flat when rough).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "penumbra/ibl.h"

namespace penumbra::ibl {
namespace {

constexpr double kPiD = std::numbers::pi;

TEST(SheenTest, CharlieDistributionIsNormalised) {
  // integral over the hemisphere of D(h) (n.h) d omega_h = 1, in polar coordinates.
  for (float r : {0.07f, 0.3f, 0.6f, 1.0f}) {
    const float alpha = sheenAlpha(r);
    const int n = 20000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double theta = (i + 0.5) * (kPiD / 2.0) / n;
      sum += sheenD(static_cast<float>(std::cos(theta)), alpha) * std::cos(theta) *
             std::sin(theta) * (kPiD / 2.0) / n * 2.0 * kPiD;
    }
    EXPECT_NEAR(sum, 1.0, 2e-3) << "roughness " << r;
  }
}

// E(n.v) by a midpoint rule over the hemisphere of light directions (no sampling shared with
// the implementation).
double bruteForceAlbedo(float nv, float r) {
  const float alpha = sheenAlpha(r);
  const glm::vec3 v(std::sqrt(1.0f - nv * nv), 0.0f, nv);
  const int nt = 400, np = 400;
  double sum = 0.0;
  for (int i = 0; i < nt; ++i) {
    const double theta = (i + 0.5) * (kPiD / 2.0) / nt;
    for (int j = 0; j < np; ++j) {
      const double phi = (j + 0.5) * 2.0 * kPiD / np;
      const glm::vec3 l(static_cast<float>(std::sin(theta) * std::cos(phi)),
                        static_cast<float>(std::sin(theta) * std::sin(phi)),
                        static_cast<float>(std::cos(theta)));
      const glm::vec3 h = glm::normalize(v + l);
      sum += sheenD(h.z, alpha) * sheenV(nv, l.z, alpha) * l.z * std::sin(theta) *
             (kPiD / 2.0 / nt) * (2.0 * kPiD / np);
    }
  }
  return std::min(sum, 1.0);
}

TEST(SheenTest, AlbedoMatchesBruteForceQuadrature) {
  for (float r : {0.2f, 0.5f, 1.0f}) {
    for (float nv : {0.15f, 0.5f, 0.9f}) {
      const double expected = bruteForceAlbedo(nv, r);
      EXPECT_NEAR(integrateSheenAlbedo(nv, r, 1024), expected, 0.01 + 0.02 * expected)
          << "n.v " << nv << ", roughness " << r;
    }
  }
}

TEST(SheenTest, AlbedoTableIsBoundedAndShapedLikeSheen) {
  const int size = 16;
  const Image lut = computeSheenLut(size, 256);
  ASSERT_EQ(lut.channels, 1);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float e = lut.pixel(x, y)[0];
      EXPECT_GE(e, 0.0f);
      EXPECT_LE(e, 1.0f);
    }
  }
  // Grazing views see more sheen than head-on ones, at every roughness.
  for (int y = 0; y < size; ++y) EXPECT_GT(lut.pixel(0, y)[0], lut.pixel(size - 1, y)[0]) << y;
  // A smooth sheen is a thin rim: almost nothing head-on; a rough one is seen from everywhere.
  EXPECT_LT(lut.pixel(size - 1, 1)[0], 0.01f);
  EXPECT_GT(lut.pixel(size - 1, size - 1)[0], 0.1f);
}

}  // namespace
}  // namespace penumbra::ibl
