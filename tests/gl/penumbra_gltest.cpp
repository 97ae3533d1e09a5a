// The converged penumbra of an area light behind an occluder matches the visibility integral:
// a rect light (0.4 m square, 1 m up) over a floor, a plate at 0.5 m covering x < 0. The ratio
// shadowed / unshadowed along a line across the penumbra is compared with brute-force
// quadrature of  integral V cos cos / r^2 dA  /  integral cos cos / r^2 dA.
#include <cmath>

#include <gtest/gtest.h>

#include "penumbra/environment.h"
#include "passes/camera_math.h"
#include "render_fixture.h"

namespace penumbra::test {
namespace {

constexpr float kLightY = 1.0f, kPlateY = 0.5f, kLightSize = 0.4f;

double visibleFraction(double x, double z, bool occluded, int res = 200) {
  double vis = 0.0, all = 0.0;
  for (int j = 0; j < res; ++j) {
    for (int i = 0; i < res; ++i) {
      const double lx = ((i + 0.5) / res - 0.5) * kLightSize;
      const double lz = ((j + 0.5) / res - 0.5) * kLightSize;
      const double dx = lx - x, dy = kLightY, dz = lz - z;
      const double r2 = dx * dx + dy * dy + dz * dz;
      const double w = (dy / std::sqrt(r2)) * (dy / std::sqrt(r2)) / r2;  // cos_p cos_l / r^2
      all += w;
      // The segment crosses the plate's height at this x; the plate covers x < 0.
      const double xc = x + dx * (kPlateY / kLightY);
      if (!occluded || xc >= 0.0) vis += w;
    }
  }
  return vis / all;
}

Scene scene(bool withPlate) {
  Scene s;
  s.materials.push_back(lambert(glm::vec3(0.8f)));
  s.meshes.push_back(quadMesh(8.0f, 0.0f, 0));
  if (withPlate)
    s.meshes.push_back(boxMesh({-4.0f, kPlateY, -4.0f}, {0.0f, kPlateY + 0.02f, 4.0f}, 0));
  Light l;
  l.type = LightType::Rect;
  l.intensity = 5.0f;
  l.position = {0, kLightY, 0};
  l.direction = {0, -1, 0};
  l.right = {1, 0, 0};
  l.up = {0, 0, -1};
  l.width = l.height = kLightSize;
  s.lights.push_back(l);
  finishScene(s);
  return s;
}

class PenumbraGLTest : public GlFixture {};

TEST_F(PenumbraGLTest, ConvergedPenumbraMatchesVisibilityIntegral) {
  RenderSettings rs;
  rs.width = 96;
  rs.height = 48;
  rs.toneMapper = ToneMapper::None;
  rs.progressive.frames = 128;
  rs.progressive.lightSamples = 64;
  rs.progressive.shadowMapSize = 1024;
  rs.progressive.screenSpaceIndirect = false;
  const Camera cam = lookAtCamera({0, 0.3f, 1.2f}, {0, 0, 0}, 40.0f);
  const PackedEnvironment black = uniformEnvironment(glm::vec3(0.0f));
  auto lit = renderRadiance(scene(false), black, cam, rs);
  auto shadowed = renderRadiance(scene(true), black, cam, rs);
  ASSERT_TRUE(lit.ok() && shadowed.ok());

  const CameraMatrices cm = cameraMatrices(cam, rs.width, rs.height, {0, 0});
  const glm::mat4 inv = glm::inverse(cm.projection * cm.view);
  const int row = rs.height / 2;
  int inPenumbra = 0;
  double worst = 0.0;
  for (int x = 0; x < rs.width; ++x) {
    // Unproject the pixel centre (row 0 = top) and intersect the floor y = 0.
    const float ndcX = (x + 0.5f) / rs.width * 2.0f - 1.0f;
    const float ndcY = 1.0f - (row + 0.5f) / rs.height * 2.0f;
    glm::vec4 a = inv * glm::vec4(ndcX, ndcY, -1.0f, 1.0f),
              b = inv * glm::vec4(ndcX, ndcY, 0.5f, 1.0f);
    glm::vec3 p0 = glm::vec3(a) / a.w, p1 = glm::vec3(b) / b.w;
    const float t = p0.y / (p0.y - p1.y);
    const glm::vec3 floor = p0 + (p1 - p0) * t;
    const double expected =
        visibleFraction(floor.x, floor.z, true) / visibleFraction(floor.x, floor.z, false);
    const double measured = shadowed->pixel(x, row)[0] / std::max(lit->pixel(x, row)[0], 1e-6f);
    if (expected > 0.05 && expected < 0.95) ++inPenumbra;
    worst = std::max(worst, std::abs(measured - expected));
    EXPECT_NEAR(measured, expected, 0.06) << "floor x " << floor.x;
  }
  EXPECT_GT(inPenumbra, 10) << "the line must cross the penumbra";
  RecordProperty("max_abs_error", std::to_string(worst));
}

}  // namespace
}  // namespace penumbra::test
