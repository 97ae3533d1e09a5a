// Unshadowed area-light shading against closed forms: the irradiance of a disk on a parallel
// plane below its centre is E = pi L r^2 / (r^2 + h^2); a Lambertian plane of albedo 1 then
// reflects L r^2 / (r^2 + h^2).
#include <cmath>

#include <gtest/gtest.h>

#include "penumbra/environment.h"
#include "render_fixture.h"

namespace penumbra::test {
namespace {

class AreaLightGLTest : public GlFixture {};

Scene planeUnderLight(LightType type, float size, float height) {
  Scene s;
  s.materials.push_back(lambert(glm::vec3(1.0f)));
  s.meshes.push_back(quadMesh(40.0f, 0.0f, 0));
  Light l;
  l.type = type;
  l.intensity = 1.0f;
  l.position = {0, height, 0};
  l.direction = {0, -1, 0};
  l.right = {1, 0, 0};
  l.up = {0, 0, -1};
  l.width = l.height = size;
  s.lights.push_back(l);
  finishScene(s);
  return s;
}

RenderSettings oneFrame() {
  RenderSettings rs;
  rs.width = rs.height = 33;
  rs.progressive.frames = 1;
  rs.toneMapper = ToneMapper::None;
  return rs;
}

float centre(const Image& img) { return img.pixel(img.width / 2, img.height / 2)[0]; }

TEST_F(AreaLightGLTest, DiskIrradianceMatchesAnalyticFormFactor) {
  const Camera cam = lookAtCamera({0, 0.05f, 0.0001f}, {0, 0, 0}, 10.0f);
  for (float h : {0.25f, 0.5f, 1.0f, 2.0f}) {
    const float r = 0.5f;
    auto img = renderRadiance(planeUnderLight(LightType::Disk, 2 * r, h),
                              uniformEnvironment(glm::vec3(0.0f)), cam, oneFrame());
    ASSERT_TRUE(img.ok()) << img.message();
    const float expected = r * r / (r * r + h * h);
    EXPECT_NEAR(centre(*img), expected, 0.02f * expected) << "height " << h;
  }
}

TEST_F(AreaLightGLTest, RectIrradianceMatchesAnalyticFormFactor) {
  // Square of side a at height h, point below the centre (four corner rectangles):
  // E = (2L) * 4 * [ x/sqrt(1+x^2) atan(y/sqrt(1+x^2)) + ... ] / 4 with x = y = a / (2h).
  const Camera cam = lookAtCamera({0, 0.05f, 0.0001f}, {0, 0, 0}, 10.0f);
  const float a = 1.0f, h = 0.5f;
  auto img = renderRadiance(planeUnderLight(LightType::Rect, a, h),
                            uniformEnvironment(glm::vec3(0.0f)), cam, oneFrame());
  ASSERT_TRUE(img.ok()) << img.message();
  const double x = a / (2 * h), y = a / (2 * h);
  const double fCorner = (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                          y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
                         (2 * M_PI);
  const double expected = 4.0 * fCorner;  // albedo 1: radiance = L * F
  EXPECT_NEAR(centre(*img), expected, 0.02 * expected);
}

}  // namespace
}  // namespace penumbra::test
