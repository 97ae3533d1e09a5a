// Sun extraction (ibl::extractSun) and its place in the packed file: a synthetic panorama with
// a known disk gives back its direction, size and energy; panoramas without a sun are left
// alone; the manifest carries the sun (version 2) and version-1 files still load.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include <glm/geometric.hpp>

#include "penumbra/environment_format.h"
#include "penumbra/ibl.h"
#include "test_support.h"

namespace penumbra {
namespace {

constexpr double kPi = 3.14159265358979323846;

double luminance(const float* p) {
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// Luminance-weighted integral over the sphere of a panorama (per pixel solid angle).
glm::dvec3 integral(const Image& image) {
  glm::dvec3 sum(0.0);
  for (int y = 0; y < image.height; ++y) {
    const double omega =
        (2.0 * kPi / image.width) * (kPi / image.height) * std::sin(kPi * (y + 0.5) / image.height);
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.pixel(x, y);
      sum += glm::dvec3(p[0], p[1], p[2]) * omega;
    }
  }
  return sum;
}

// A sky gradient with a disk of the given angular radius and radiance, the disk's pixels
// covered by 8x8 supersampling (so the edge is antialiased, as in a real capture).
Image skyWithSun(int width, const glm::vec3& sunDir, double radius, const glm::vec3& radiance) {
  const int height = width / 2;
  Image image(width, height, 3);
  const double cosR = std::cos(radius);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::vec3 d = ibl::panoramaDirection((x + 0.5f) / width, (y + 0.5f) / height);
      glm::vec3 c = d.y > 0 ? glm::vec3(0.4f, 0.6f, 1.0f) * (0.5f + 0.5f * d.y)
                            : glm::vec3(0.2f, 0.18f, 0.15f);
      if (glm::dot(d, sunDir) > std::cos(radius + 0.02)) {
        int inside = 0;
        for (int j = 0; j < 8; ++j) {
          for (int i = 0; i < 8; ++i) {
            const glm::vec3 s =
                ibl::panoramaDirection((x + (i + 0.5f) / 8) / width, (y + (j + 0.5f) / 8) / height);
            inside += glm::dot(s, sunDir) > cosR ? 1 : 0;
          }
        }
        c += radiance * (inside / 64.0f);
      }
      float* p = image.pixel(x, y);
      p[0] = c.x;
      p[1] = c.y;
      p[2] = c.z;
    }
  }
  return image;
}

TEST(IblSunTest, FindsAKnownDiskAndConservesEnergy) {
  const glm::vec3 dir = glm::normalize(glm::vec3(0.5f, 0.7f, -0.3f));
  const double radius = 1.5 * kPi / 180.0;
  const glm::vec3 radiance(30000.0f, 27000.0f, 24000.0f);
  const Image original = skyWithSun(1024, dir, radius, radiance);
  Image image = original;
  const auto sun = ibl::extractSun(image);
  ASSERT_TRUE(sun.has_value());
  const double angle = std::acos(std::min(1.0f, glm::dot(sun->direction, dir))) * 180.0 / kPi;
  EXPECT_LT(angle, 0.5) << "direction off by " << angle << " degrees";
  EXPECT_NEAR(sun->angularRadius / radius, 1.0, 0.1);
  // Energy: the sun plus what stays in the panorama is what was there (1 %), and the sun
  // holds the disk's energy above the threshold (2 pi (1 - cos r) L).
  const glm::dvec3 before = integral(original), after = integral(image);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR((after[c] + sun->irradiance[c]) / before[c], 1.0, 0.01) << "channel " << c;
    const double disk = 2.0 * kPi * (1.0 - std::cos(radius)) * radiance[c];
    EXPECT_NEAR(sun->irradiance[c] / disk, 1.0, 0.01) << "channel " << c;
  }
  // Nothing above the threshold is left.
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      ASSERT_LE(luminance(image.pixel(x, y)), sun->threshold * 1.0001);
    }
  }
}

TEST(IblSunTest, NoSunInSoftOrUniformLight) {
  // A uniform sky and a large softbox (20 degrees) have no sun; the panorama is untouched.
  Image uniform(64, 32, 3);
  for (float& v : uniform.pixels) v = 1.0f;
  Image copy = uniform;
  EXPECT_FALSE(ibl::extractSun(copy).has_value());
  EXPECT_EQ(copy.pixels, uniform.pixels);
  const Image softbox =
      skyWithSun(256, glm::vec3(0, 1, 0), 20.0 * kPi / 180.0, glm::vec3(50.0f, 50.0f, 50.0f));
  copy = softbox;
  EXPECT_FALSE(ibl::extractSun(copy).has_value());
  EXPECT_EQ(copy.pixels, softbox.pixels);
  // An explicit threshold takes even the softbox; 0 takes nothing.
  EXPECT_TRUE(ibl::extractSun(copy, {.threshold = 10.0f}).has_value());
  Image off = softbox;
  EXPECT_FALSE(ibl::extractSun(off, {.threshold = 0.0f}).has_value());
}

TEST(IblSunTest, PrefilterKeepsTheSunOutOfTheCube) {
  const glm::vec3 dir = glm::normalize(glm::vec3(-0.2f, 0.9f, 0.3f));
  const Image pano = skyWithSun(256, dir, 2.0 * kPi / 180.0, glm::vec3(20000.0f));
  ibl::PrefilterOptions options;
  options.faceSize = 32;
  options.samples = 16;
  auto with = ibl::prefilterCpu(pano, options);
  ASSERT_TRUE(with.ok()) << with.message();
  ASSERT_TRUE(with->sun.has_value());
  options.sunThreshold = 0.0f;
  auto without = ibl::prefilterCpu(pano, options);
  ASSERT_TRUE(without.ok());
  EXPECT_FALSE(without->sun.has_value());
  // The SH's DC term (mean radiance) loses exactly the sun's share: E_sun / (4 pi).
  const double y00 = 0.282095;
  for (int c = 0; c < 3; ++c) {
    const double lost = (without->sh.c[0][c] - with->sh.c[0][c]) * y00;
    EXPECT_NEAR(lost / (with->sun->irradiance[c] / (4.0 * kPi)), 1.0, 0.03) << "channel " << c;
  }
}

TEST(IblSunTest, PackedFileCarriesTheSunAndVersionOneStillLoads) {
  const Image pano = skyWithSun(128, glm::vec3(0, 1, 0), 3.0 * kPi / 180.0, glm::vec3(5000.0f));
  ibl::PrefilterOptions options;
  options.faceSize = 16;
  options.samples = 8;
  auto env = ibl::prefilterCpu(pano, options);
  ASSERT_TRUE(env.ok() && env->sun.has_value());
  auto bytes = encodePackedEnvironment(*env);
  ASSERT_TRUE(bytes.ok()) << bytes.message();
  const std::string text(bytes->begin(), bytes->begin() + 400);
  EXPECT_NE(text.find("\"version\":2"), std::string::npos);
  auto back = readPackedEnvironmentFromMemory(*bytes, "sun.hdr");
  ASSERT_TRUE(back.ok()) << back.message();
  ASSERT_TRUE(back->sun.has_value());
  EXPECT_EQ(back->sun->direction, env->sun->direction);
  EXPECT_EQ(back->sun->irradiance, env->sun->irradiance);
  EXPECT_EQ(back->sun->angularRadius, env->sun->angularRadius);
  // Without a sun the file stays version 1, byte for byte what older writers made.
  env->sun.reset();
  auto v1 = encodePackedEnvironment(*env);
  ASSERT_TRUE(v1.ok());
  EXPECT_NE(std::string(v1->begin(), v1->begin() + 400).find("\"version\":1"), std::string::npos);
  // A version-1 file written before the sun existed (the fuzz seed) loads, without a sun.
  std::ifstream in(test::sourceDir() + "/tests/fuzz/corpus/packed_env/uniform_size4.hdr",
                   std::ios::binary);
  const std::vector<uint8_t> old((std::istreambuf_iterator<char>(in)), {});
  ASSERT_FALSE(old.empty());
  auto oldEnv = readPackedEnvironmentFromMemory(old, "uniform_size4.hdr");
  ASSERT_TRUE(oldEnv.ok()) << oldEnv.message();
  EXPECT_FALSE(oldEnv->sun.has_value());
}

}  // namespace
}  // namespace penumbra
