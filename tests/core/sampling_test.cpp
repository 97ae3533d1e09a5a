// Sampling routines of renderer/src/ibl/sampling.h: every density integrates to 1 (numerical
// quadrature) and every sampler draws according to its density (histogram test).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "ibl/sampling.h"

namespace penumbra::ibl {
namespace {

// Integral over the hemisphere (or the sphere) of f(direction), midpoint rule in
// (cos theta, phi), which is uniform in solid angle: d omega = d(cos theta) d phi.
double integrateSphere(const std::function<double(const glm::vec3&)>& f, int nCos, int nPhi,
                       double cosMin = -1.0) {
  double sum = 0.0;
  const double dc = (1.0 - cosMin) / nCos;
  const double dp = 2.0 * std::numbers::pi / nPhi;
  for (int i = 0; i < nCos; ++i) {
    const double c = cosMin + (i + 0.5) * dc;
    const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
    for (int j = 0; j < nPhi; ++j) {
      const double p = (j + 0.5) * dp;
      sum += f(glm::vec3(s * std::cos(p), s * std::sin(p), c));
    }
  }
  return sum * dc * dp;
}

// 1D integral over cos theta in [0, 1] of g(cos) * 2 pi, for isotropic densities with sharp
// peaks at cos = 1: substitution t = 1 - cos with quadratic spacing resolves the peak.
double integrateIsotropic(const std::function<double(double)>& g, int n) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double a = static_cast<double>(i) / n;
    const double b = static_cast<double>(i + 1) / n;
    const double t0 = a * a;  // t = 1 - cos in [0, 1], denser near the peak
    const double t1 = b * b;
    const double tm = 0.5 * (t0 + t1);
    sum += g(1.0 - tm) * (t1 - t0);
  }
  return sum * 2.0 * std::numbers::pi;
}

TEST(SamplingTest, RadicalInverseAndHammersley) {
  EXPECT_FLOAT_EQ(radicalInverse(0), 0.0f);
  EXPECT_FLOAT_EQ(radicalInverse(1), 0.5f);
  EXPECT_FLOAT_EQ(radicalInverse(2), 0.25f);
  EXPECT_FLOAT_EQ(radicalInverse(3), 0.75f);
  EXPECT_FLOAT_EQ(radicalInverse(5), 0.625f);
  for (uint32_t i = 0; i < 64; ++i) {
    const glm::vec2 u = hammersley(i, 64);
    EXPECT_GT(u.x, 0.0f);
    EXPECT_LT(u.x, 1.0f);
    EXPECT_GE(u.y, 0.0f);
    EXPECT_LT(u.y, 1.0f);
  }
}

TEST(SamplingTest, OrthonormalBasis) {
  std::mt19937 rng(7);
  std::normal_distribution<float> normal;
  for (int i = 0; i < 1000; ++i) {
    glm::vec3 n(normal(rng), normal(rng), normal(rng));
    if (i == 0) n = glm::vec3(0, 0, -1);  // the branchless form's special case
    if (i == 1) n = glm::vec3(0, 0, 1);
    n = glm::normalize(n);
    glm::vec3 t, b;
    orthonormalBasis(n, t, b);
    EXPECT_NEAR(glm::dot(t, t), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(b, b), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(t, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(b, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(t, b), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(glm::cross(t, b), n), 1.0f, 1e-4f);  // right-handed
  }
}

TEST(SamplingTest, CosinePdfIntegratesToOne) {
  const double integral =
      integrateSphere([](const glm::vec3& w) { return pdfCosineHemisphere(w.z); }, 400, 64, 0.0);
  EXPECT_NEAR(integral, 1.0, 1e-4);
}

TEST(SamplingTest, GgxHalfVectorPdfIntegratesToOne) {
  for (float alpha : {0.02f, 0.1f, 0.3f, 0.6f, 1.0f}) {
    const double integral =
        integrateIsotropic([&](double c) { return pdfGgxD(static_cast<float>(c), alpha); }, 20000);
    EXPECT_NEAR(integral, 1.0, 2e-3) << "alpha " << alpha;
  }
}

TEST(SamplingTest, GgxReflectedPdfIntegratesToValidHalfVectors) {
  // Over the whole sphere of l for a fixed v, the reflected density integrates to the
  // probability that a sampled h faces v (v.h > 0; the others give no direction): 1 for v = n.
  for (float alpha : {0.3f, 0.6f, 1.0f}) {
    for (float theta : {0.0f, 0.7f, 1.3f}) {
      const glm::vec3 v(std::sin(theta), 0.0f, std::cos(theta));
      const double integral = integrateSphere(
          [&](const glm::vec3& l) {
            const glm::vec3 sum = v + l;
            if (glm::dot(sum, sum) < 1e-12f) return 0.0;
            const glm::vec3 h = glm::normalize(sum);
            return static_cast<double>(pdfGgxDReflected(h.z, glm::dot(v, h), alpha));
          },
          1500, 600);
      const double valid = integrateSphere(
          [&](const glm::vec3& h) {
            return glm::dot(v, h) > 0.0f ? static_cast<double>(pdfGgxD(h.z, alpha)) : 0.0;
          },
          1500, 600, 0.0);
      if (theta == 0.0f) {
        EXPECT_NEAR(valid, 1.0, 5e-3);
      }
      EXPECT_NEAR(integral, valid, 1e-2) << "alpha " << alpha << " theta " << theta;
    }
  }
}

TEST(SamplingTest, VndfPdfIntegratesToOne) {
  for (float alpha : {0.2f, 0.5f, 1.0f}) {
    for (float theta : {0.1f, 0.8f, 1.4f}) {
      const glm::vec3 v(std::sin(theta), 0.0f, std::cos(theta));
      const double integral = integrateSphere(
          [&](const glm::vec3& h) { return static_cast<double>(pdfGgxVndf(v, h, alpha)); }, 2000,
          400, 0.0);
      EXPECT_NEAR(integral, 1.0, 5e-3) << "alpha " << alpha << " theta " << theta;
    }
  }
}

TEST(SamplingTest, SmithG2MatchesLambdaForm) {
  for (float alpha : {0.05f, 0.3f, 1.0f}) {
    for (float nv : {0.05f, 0.4f, 0.9f}) {
      for (float nl : {0.1f, 0.5f, 1.0f}) {
        const float expected = 1.0f / (1.0f + smithLambda(nv, alpha) + smithLambda(nl, alpha));
        EXPECT_NEAR(smithG2(nv, nl, alpha), expected, 1e-5f);
        EXPECT_NEAR(visibilitySmithGgx(nv, nl, alpha), expected / (4.0f * nv * nl), 1e-4f);
        EXPECT_NEAR(smithG1(nv, alpha), 1.0f / (1.0f + smithLambda(nv, alpha)), 1e-5f);
      }
    }
  }
}

// Histogram test: draw with a sampler, bin in (cos theta, phi) and compare each bin's
// frequency with the density integrated over the bin.
void expectMatchesPdf(const std::function<glm::vec3(const glm::vec2&)>& sample,
                      const std::function<double(const glm::vec3&)>& pdf, const char* name) {
  constexpr int kCosBins = 12;
  constexpr int kPhiBins = 12;
  constexpr int kSamples = 200000;
  std::vector<double> observed(kCosBins * kPhiBins, 0.0);
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int i = 0; i < kSamples; ++i) {
    const glm::vec3 w = sample({uniform(rng), uniform(rng)});
    ASSERT_NEAR(glm::length(w), 1.0f, 1e-4f) << name;
    ASSERT_GE(w.z, -1e-6f) << name;
    double phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2.0 * std::numbers::pi;
    const int ci = std::min(kCosBins - 1, static_cast<int>(std::max(0.0f, w.z) * kCosBins));
    const int pi =
        std::min(kPhiBins - 1, static_cast<int>(phi / (2.0 * std::numbers::pi) * kPhiBins));
    observed[ci * kPhiBins + pi] += 1.0;
  }
  double total = 0.0;
  for (int ci = 0; ci < kCosBins; ++ci) {
    for (int pi = 0; pi < kPhiBins; ++pi) {
      // Quadrature of the density over the bin.
      constexpr int kSub = 24;
      double expected = 0.0;
      for (int a = 0; a < kSub; ++a) {
        const double c = (ci + (a + 0.5) / kSub) / kCosBins;
        const double s = std::sqrt(1.0 - c * c);
        for (int b = 0; b < kSub; ++b) {
          const double p = (pi + (b + 0.5) / kSub) / kPhiBins * 2.0 * std::numbers::pi;
          expected += pdf(glm::vec3(s * std::cos(p), s * std::sin(p), c));
        }
      }
      expected *= (1.0 / kCosBins / kSub) * (2.0 * std::numbers::pi / kPhiBins / kSub);
      total += expected;
      const double frequency = observed[ci * kPhiBins + pi] / kSamples;
      // Five standard deviations of a binomial count, plus quadrature slack.
      const double sigma = std::sqrt(std::max(expected, 1e-6) * (1.0 - expected) / kSamples);
      EXPECT_NEAR(frequency, expected, 5.0 * sigma + 2e-3 * expected + 1e-4)
          << name << " bin cos " << ci << " phi " << pi;
    }
  }
  EXPECT_NEAR(total, 1.0, 1e-2) << name;
}

TEST(SamplingTest, CosineSamplesFollowPdf) {
  expectMatchesPdf([](const glm::vec2& u) { return sampleCosineHemisphere(u); },
                   [](const glm::vec3& w) { return pdfCosineHemisphere(w.z); }, "cosine");
}

TEST(SamplingTest, GgxSamplesFollowPdf) {
  const float alpha = 0.5f;
  expectMatchesPdf([&](const glm::vec2& u) { return sampleGgxD(u, alpha); },
                   [&](const glm::vec3& h) { return pdfGgxD(h.z, alpha); }, "ggx D");
}

TEST(SamplingTest, VndfSamplesFollowPdf) {
  const float alpha = 0.6f;
  const glm::vec3 v = glm::normalize(glm::vec3(0.8f, 0.3f, 0.5f));
  expectMatchesPdf([&](const glm::vec2& u) { return sampleGgxVndf(v, u, alpha); },
                   [&](const glm::vec3& h) { return pdfGgxVndf(v, h, alpha); }, "ggx vndf");
}

TEST(SamplingTest, AnisotropicGgxPdfIntegratesToOneAndMatchesIsotropic) {
  for (const auto& [at, ab] :
       {std::pair{0.6f, 0.6f}, std::pair{0.8f, 0.2f}, std::pair{1.0f, 0.3f}}) {
    const double total = integrateSphere(
        [&](const glm::vec3& h) { return pdfGgxDAnisotropic(h, at, ab); }, 2000, 256, 0.0);
    EXPECT_NEAR(total, 1.0, 1e-2) << at << " " << ab;
  }
  for (const float c : {0.2f, 0.6f, 0.95f}) {
    const glm::vec3 h(std::sqrt(1.0f - c * c), 0.0f, c);
    EXPECT_NEAR(ggxDAnisotropic(h, 0.4f, 0.4f) / ggxD(c, 0.4f), 1.0, 1e-5);
  }
}

TEST(SamplingTest, AnisotropicGgxSamplesFollowPdf) {
  const float at = 0.9f, ab = 0.25f;
  expectMatchesPdf([&](const glm::vec2& u) { return sampleGgxDAnisotropic(u, at, ab); },
                   [&](const glm::vec3& h) { return pdfGgxDAnisotropic(h, at, ab); },
                   "anisotropic ggx D");
}

TEST(SamplingTest, ExpectationOfWeightedSamples) {
  // E[f / pdf] = integral of f: f = cos^2 over the hemisphere is 2 pi / 3.
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  constexpr int kN = 200000;
  double cosineEstimate = 0.0;
  double ggxEstimate = 0.0;
  for (int i = 0; i < kN; ++i) {
    const glm::vec2 u(uniform(rng), uniform(rng));
    const glm::vec3 w = sampleCosineHemisphere(u);
    cosineEstimate += w.z * w.z / pdfCosineHemisphere(w.z);
    // GGX D sampling of f = D(h) (n.h)^2: E = integral D (n.h)^2 = E_pdf[n.h].
    const glm::vec3 h = sampleGgxD(u, 0.4f);
    ggxEstimate += ggxD(h.z, 0.4f) * h.z * h.z / pdfGgxD(h.z, 0.4f);
  }
  EXPECT_NEAR(cosineEstimate / kN, 2.0 * std::numbers::pi / 3.0, 5e-3);
  const double ggxExact =
      integrateIsotropic([](double c) { return ggxD(static_cast<float>(c), 0.4f) * c * c; }, 20000);
  EXPECT_NEAR(ggxEstimate / kN, ggxExact, 5e-3 * ggxExact);
}

}  // namespace
}  // namespace penumbra::ibl
