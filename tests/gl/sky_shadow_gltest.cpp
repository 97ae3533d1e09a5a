// Sky shadows: under a uniform sky, a square plate of half-size a at height h = a over a floor
// hides the part of the sky its form factor says from the floor point under its centre; the
// floor there converges to albedo x (1 - F) (F = 0.554 for a = h), and without sky shadows it
// stays at the albedo (the occlusion rays are kept too short to reach the plate).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "passes/camera_math.h"
#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class SkyShadowGLTest : public GlFixture {};

// Form factor from a point to a parallel rectangle with a corner straight above it, sides X
// and Y in units of the height (the standard closed form).
double cornerFormFactor(double x, double y) {
  const double a = std::sqrt(1.0 + x * x), b = std::sqrt(1.0 + y * y);
  return (x / a * std::atan(y / a) + y / b * std::atan(x / b)) / (2.0 * std::numbers::pi);
}

float floorUnderPlate(bool skyShadows, int frames) {
  Scene s;
  Material floor = lambert(glm::vec3(0.5f));
  floor.specularFactor = 0.0f;  // pure Lambert: radiance = albedo x irradiance / pi
  s.materials = {floor, lambert(glm::vec3(0.5f))};
  s.meshes.push_back(quadMesh(12.0f, 0.0f, 0));
  s.meshes.push_back(boxMesh({-1.0f, 1.0f, -1.0f}, {1.0f, 1.02f, 1.0f}, 1));
  finishScene(s);
  const Camera cam = lookAtCamera({5.0f, 0.6f, 0.01f}, {0.0f, 0.0f, 0.0f}, 20.0f);
  RenderSettings rs;
  rs.width = 64;
  rs.height = 48;
  rs.progressive.frames = frames;
  rs.progressive.occlusionDistance = 1e-4f;
  rs.progressive.screenSpaceIndirect = false;
  rs.progressive.skyShadows = skyShadows;
  rs.progressive.probeVolume = false;  // sky shadows correct the distant environment's light
  rs.showBackground = false;
  auto img = renderRadiance(s, uniformEnvironment(glm::vec3(1.0f)), cam, rs);
  EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.message());
  if (!img.ok()) return -1.0f;
  const CameraMatrices cm = cameraMatrices(cam, rs.width, rs.height, {0, 0});
  // The mean over a few points around the centre, where F changes by well under 1 %.
  float sum = 0.0f;
  for (float dz : {-0.1f, 0.0f, 0.1f}) {
    for (float dx : {-0.1f, 0.0f, 0.1f}) {
      sum += radianceAt(*img, cm.projection * cm.view, {dx, 0.0f, dz}, true);
    }
  }
  return sum / 9.0f;
}

TEST_F(SkyShadowGLTest, PlateHidesItsFormFactorOfAUniformSky) {
  const double f = 4.0 * cornerFormFactor(1.0, 1.0);
  ASSERT_NEAR(f, 0.554, 0.001);
  const float shadowed = floorUnderPlate(true, 256);
  EXPECT_NEAR(shadowed, 0.5 * (1.0 - f), 0.05 * 0.5 * (1.0 - f));  // measured: 1.2 % off
  EXPECT_NEAR(floorUnderPlate(false, 16), 0.5f, 0.01f);
}

}  // namespace
}  // namespace penumbra::test
