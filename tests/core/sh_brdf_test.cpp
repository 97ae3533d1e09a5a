// Spherical-harmonic irradiance (basis orthonormality, the pi convention, exactness for a
// band-limited environment) and the DFG lookup table against brute-force quadrature.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <numbers>

#include "ibl/sampling.h"
#include "penumbra/ibl.h"

namespace penumbra::ibl {
namespace {

Cubemap cubeOf(int size, const std::function<glm::vec3(const glm::vec3&)>& radiance) {
  Cubemap cube(size, 1);
  for (int f = 0; f < kFaceCount; ++f) {
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const glm::vec3 v = radiance(texelDirection(f, x, y, size));
        float* p = cube.face(0, f).pixel(x, y);
        p[0] = v.x, p[1] = v.y, p[2] = v.z;
      }
    }
  }
  return cube;
}

TEST(ShTest, BasisIsOrthonormal) {
  const int size = 48;
  double gram[9][9] = {};
  for (int f = 0; f < kFaceCount; ++f) {
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const auto b = shBasis(texelDirection(f, x, y, size));
        const double w = texelSolidAngle(x, y, size);
        for (int i = 0; i < 9; ++i) {
          for (int j = 0; j < 9; ++j) gram[i][j] += w * b[i] * b[j];
        }
      }
    }
  }
  for (int i = 0; i < 9; ++i) {
    for (int j = 0; j < 9; ++j) EXPECT_NEAR(gram[i][j], i == j ? 1.0 : 0.0, 2e-3) << i << "," << j;
  }
}

TEST(ShTest, ConstantEnvironmentGivesPiL) {
  const glm::vec3 l(0.3f, 1.0f, 4.0f);
  const ShCoefficients sh = projectSh(cubeOf(8, [&](const glm::vec3&) { return l; }));
  for (int i = 1; i < 9; ++i) EXPECT_NEAR(glm::length(sh.c[i]), 0.0f, 1e-5f) << i;
  for (const glm::vec3 n :
       {glm::vec3(0, 0, 1), glm::vec3(0, 1, 0), glm::normalize(glm::vec3(-1, 1, 2))}) {
    const glm::vec3 e = evaluateIrradiance(sh, n);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(e[k] / (kPi * l[k]), 1.0f, 1e-3f);
    const glm::vec3 back = evaluateShRadiance(sh, n);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], l[k], 1e-3f * l[k]);
  }
}

TEST(ShTest, BandLimitedEnvironmentIrradianceIsExact) {
  // Radiance made of bands 0..2 only: the 9 coefficients hold it exactly, so SH irradiance must
  // match the brute-force cosine integral of the same cube map.
  const auto radiance = [](const glm::vec3& d) {
    const float v = 1.0f + 0.6f * d.y + 0.3f * d.x * d.z + 0.2f * (3.0f * d.y * d.y - 1.0f);
    return glm::vec3(v, 0.5f * v, 2.0f);
  };
  const int size = 64;
  const Cubemap cube = cubeOf(size, radiance);
  const ShCoefficients sh = projectSh(cube);
  for (const glm::vec3 n :
       {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::normalize(glm::vec3(1, 0.3f, -0.5f))}) {
    glm::dvec3 e(0.0);
    for (int f = 0; f < kFaceCount; ++f) {
      for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
          const glm::vec3 l = texelDirection(f, x, y, size);
          const float c = glm::dot(n, l);
          if (c > 0.0f) e += glm::dvec3(radiance(l)) * (c * texelSolidAngle(x, y, size));
        }
      }
    }
    const glm::vec3 sh9 = evaluateIrradiance(sh, n);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(sh9[k] / e[k], 1.0, 2e-3) << "channel " << k;
  }
}

TEST(ShTest, JsonListsNineCoefficients) {
  ShCoefficients sh;
  for (int i = 0; i < 9; ++i) sh.c[i] = glm::vec3(i, i + 0.5f, -i);
  const auto j = nlohmann::json::parse(shToJson(sh));
  ASSERT_EQ(j["coefficients"].size(), 9u);
  EXPECT_FLOAT_EQ(j["coefficients"][4][1].get<float>(), 4.5f);
  EXPECT_NE(j["convention"].get<std::string>().find("pi"), std::string::npos);
}

// Split-sum terms by quadrature over l in (theta, phi): A = integral (1 - Fc) f cos,
// B = integral Fc f cos, with f = D G2 / (4 nv nl) (F0 = 1 inside the integrand).
glm::dvec2 dfgQuadrature(double nv, double roughness) {
  const float alpha = static_cast<float>(roughness * roughness);
  const glm::vec3 v(static_cast<float>(std::sqrt(1.0 - nv * nv)), 0.0f, static_cast<float>(nv));
  constexpr int kTheta = 800;
  constexpr int kPhi = 400;
  glm::dvec2 sum(0.0);
  for (int i = 0; i < kTheta; ++i) {
    // Uniform in cos theta: d omega = d(cos) d phi.
    const double c = (i + 0.5) / kTheta;
    const double s = std::sqrt(1.0 - c * c);
    for (int j = 0; j < kPhi; ++j) {
      const double p = (j + 0.5) / kPhi * std::numbers::pi;  // symmetric in phi: half circle
      const glm::vec3 l(static_cast<float>(s * std::cos(p)), static_cast<float>(s * std::sin(p)),
                        static_cast<float>(c));
      const glm::vec3 h = glm::normalize(v + l);
      const double vh = glm::dot(v, h);
      const double f =
          ggxD(h.z, alpha) * visibilitySmithGgx(static_cast<float>(nv), l.z, alpha) * c;
      const double fc = std::pow(1.0 - vh, 5.0);
      sum += glm::dvec2((1.0 - fc) * f, fc * f);
    }
  }
  return sum * (1.0 / kTheta) * (2.0 * std::numbers::pi / kPhi);
}

TEST(BrdfLutTest, MatchesBruteForceQuadrature) {
  const int size = 32;
  const Image lut = computeBrdfLut({.size = size, .samples = 512, .threads = 0});
  ASSERT_EQ(lut.width, size);
  ASSERT_EQ(lut.channels, 3);
  // Texel (i, j) holds n.v = (i + 1/2) / size, roughness = (j + 1/2) / size.
  for (int j : {8, 15, 24, 31}) {
    for (int i : {1, 8, 16, 31}) {
      const double nv = (i + 0.5) / size;
      const double roughness = (j + 0.5) / size;
      const glm::dvec2 expected = dfgQuadrature(nv, roughness);
      const float* p = lut.pixel(i, j);
      EXPECT_NEAR(p[0], expected.x, 0.01) << "A at n.v " << nv << " roughness " << roughness;
      EXPECT_NEAR(p[1], expected.y, 0.01) << "B at n.v " << nv << " roughness " << roughness;
      EXPECT_NEAR(p[2], p[0] + p[1], 1e-5f);
    }
  }
}

TEST(BrdfLutTest, EnergyIsBoundedAndSmoothSurfacesReflectAll) {
  const Image lut = computeBrdfLut({.size = 16, .samples = 256, .threads = 0});
  for (int j = 0; j < 16; ++j) {
    for (int i = 0; i < 16; ++i) {
      const float* p = lut.pixel(i, j);
      EXPECT_GE(p[0], 0.0f);
      EXPECT_GE(p[1], 0.0f);
      EXPECT_LE(p[2], 1.0f + 1e-4f);  // single scattering never gains energy
    }
  }
  // Nearly smooth: E_ss ~ 1 (no masking to lose energy); rough: single scattering loses a
  // large part, which the B channel lets the renderer compensate.
  EXPECT_GT(lut.pixel(15, 0)[2], 0.98f);
  EXPECT_LT(lut.pixel(15, 15)[2], 0.6f);
  const glm::vec3 single = integrateDfg(0.5f, 0.5f, 512);
  EXPECT_NEAR(single.z, single.x + single.y, 1e-5f);
}

}  // namespace
}  // namespace penumbra::ibl
