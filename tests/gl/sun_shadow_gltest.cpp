// The environment's sun casts shadows: a panorama that is black but for a disk of angular
// radius r at the zenith is prefiltered (the sun is extracted), and a thin plate at height h
// over a floor shades it with a penumbra whose 10-90 % width matches the analytic one for a
// uniform disk (15 %). Turning the environment turns the sun with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "passes/camera_math.h"
#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class SunShadowGLTest : public GlFixture {};

constexpr int kSunSize = 192;

// Black panorama with a disk of radiance L and angular radius r around `dir`, antialiased.
Image sunPanorama(const glm::vec3& dir, double radius, float radiance) {
  Image image(512, 256, 3);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      int inside = 0;
      for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
          const glm::vec3 d = ibl::panoramaDirection((x + (i + 0.5f) / 4) / image.width,
                                                     (y + (j + 0.5f) / 4) / image.height);
          inside += glm::dot(d, dir) > std::cos(radius) ? 1 : 0;
        }
      }
      float* p = image.pixel(x, y);
      p[0] = p[1] = p[2] = radiance * static_cast<float>(inside) / 16.0f;
    }
  }
  return image;
}

PackedEnvironment sunEnvironment(const glm::vec3& dir, double radius) {
  ibl::PrefilterOptions options;
  options.faceSize = 32;
  options.samples = 16;
  auto env = ibl::prefilterCpu(sunPanorama(dir, radius, 2000.0f), options);
  EXPECT_TRUE(env.ok() && env->sun.has_value());
  return env.ok() ? std::move(*env) : uniformEnvironment(glm::vec3(0.0f));
}

struct PlateRender {
  Image image;
  CameraMatrices camera;
  // Bilinear, so the profile is not quantised to pixels.
  float at(glm::vec3 p) const {
    return radianceAt(image, camera.projection * camera.view, p, true);
  }
};

// A floor and a thin plate over x in [-2, 1] at height 1: its edge at x = 1 shades the floor.
PlateRender renderPlate(const PackedEnvironment& env, float rotation = 0.0f) {
  Scene s;
  s.materials = {lambert(glm::vec3(0.8f)), lambert(glm::vec3(0.5f))};
  s.meshes.push_back(quadMesh(4.0f, 0.0f, 0));
  s.meshes.push_back(boxMesh({-2.0f, 1.0f, -2.0f}, {1.0f, 1.02f, 2.0f}, 1));
  finishScene(s);
  const Camera cam = lookAtCamera({2.6f, 3.0f, 0.01f}, {1.0f, 0.0f, 0.0f}, 12.0f);
  RenderSettings rs;
  rs.width = rs.height = kSunSize;
  rs.progressive.frames = 128;
  rs.progressive.directDelay = 0.0f;
  rs.progressive.shadowMapSize = 2048;
  rs.progressive.screenSpaceIndirect = false;
  rs.environmentRotation = rotation;
  rs.showBackground = false;
  auto img = renderRadiance(s, env, cam, rs);
  EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.message());
  return {img.ok() ? std::move(*img) : Image(kSunSize, kSunSize, 4),
          cameraMatrices(cam, kSunSize, kSunSize, {0, 0})};
}

// Visible fraction of a uniform disk of (projected) radius R cut by an edge at offset s.
double diskFraction(double s) {
  s = std::clamp(s, -1.0, 1.0);
  return 1.0 - (std::acos(s) - s * std::sqrt(1.0 - s * s)) / std::numbers::pi;
}

// Offset (in units of R) where the fraction reaches f.
double diskOffset(double f) {
  double lo = -1.0, hi = 1.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (diskFraction(mid) < f ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST_F(SunShadowGLTest, PenumbraWidthFollowsTheSunsSize) {
  const double radius = 3.0 * std::numbers::pi / 180.0;
  const PackedEnvironment env = sunEnvironment({0.0f, 1.0f, 0.0f}, radius);
  ASSERT_TRUE(env.sun.has_value());
  const PlateRender r = renderPlate(env);
  (void)writeImage(outputDir() + "/sun_penumbra.png", r.image);  // to look at
  const double R = std::tan(env.sun->angularRadius);             // plate at height 1
  const auto level = [&](double from, double to) {
    double sum = 0;
    for (int i = 0; i < 9; ++i) sum += r.at({static_cast<float>(from + (to - from) * i / 8), 0, 0});
    return sum / 9;
  };
  const double shadow = level(1 - 3 * R, 1 - 2 * R), lit = level(1 + 2 * R, 1 + 3 * R);
  ASSERT_GT(lit, 10.0 * std::max(shadow, 1e-4)) << "the floor under the plate is not in shadow";
  // The measured profile's 10 % and 90 % crossings, walking out from under the plate.
  double x10 = 0, x90 = 0;
  double prevX = 1 - 2 * R, prevF = 0;
  for (int i = 1; i <= 400; ++i) {
    const double x = 1 - 2 * R + 4 * R * i / 400;
    const double f = (r.at({static_cast<float>(x), 0, 0}) - shadow) / (lit - shadow);
    if (x10 == 0 && f >= 0.1) x10 = prevX + (x - prevX) * (0.1 - prevF) / (f - prevF);
    if (x90 == 0 && f >= 0.9) x90 = prevX + (x - prevX) * (0.9 - prevF) / (f - prevF);
    prevX = x;
    prevF = f;
  }
  ASSERT_GT(x90, x10);
  const double analytic = (diskOffset(0.9) - diskOffset(0.1)) * R;
  EXPECT_NEAR((x90 - x10) / analytic, 1.0, 0.15)
      << "10-90 % penumbra " << (x90 - x10) << " against " << analytic << " for R " << R;
  // Centred on the edge's shadow (x = 1): the 50 % point within a fifth of R.
  EXPECT_NEAR(0.5 * (x10 + x90), 1.0, 0.2 * R);
}

TEST_F(SunShadowGLTest, TheSunTurnsWithTheEnvironment) {
  // A sun 45 degrees from the zenith towards -x shades the floor beyond the plate's edge (the
  // shadow falls towards +x); turned by 180 degrees it shines from +x and the floor there is lit.
  const glm::vec3 dir = glm::normalize(glm::vec3(-1.0f, 1.0f, 0.0f));
  const PackedEnvironment env = sunEnvironment(dir, 1.0 * std::numbers::pi / 180.0);
  const PlateRender a = renderPlate(env, 0.0f), b = renderPlate(env, 180.0f);
  const glm::vec3 p(1.5f, 0.0f, 0.0f);  // half a unit past the edge
  EXPECT_LT(a.at(p), 0.1f * b.at(p));
}

}  // namespace
}  // namespace penumbra::test
