// The background's lookup (background.frag): a cubic B-spline over the shown mip's texel grid,
// so a magnified small mip shows no kinks or blocks, and a uniform sky stays exactly uniform.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "penumbra/environment.h"
#include "penumbra/ibl.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class BackgroundGLTest : public GlFixture {};

constexpr int kBackgroundWidth = 192, kBackgroundHeight = 96;

// A dim panorama with a bright window around -Z: |x| < 0.3 |z| and |y| < 0.2 |z|.
PackedEnvironment windowEnvironment() {
  Image pano(256, 128, 3);
  for (int y = 0; y < pano.height; ++y) {
    for (int x = 0; x < pano.width; ++x) {
      const glm::vec3 d = ibl::panoramaDirection((x + 0.5f) / static_cast<float>(pano.width),
                                                 (y + 0.5f) / static_cast<float>(pano.height));
      const bool window = d.z < 0.0f && std::abs(d.x) < -0.3f * d.z && std::abs(d.y) < -0.2f * d.z;
      float* p = pano.pixel(x, y);
      p[0] = p[1] = p[2] = window ? 1.0f : 0.1f;
    }
  }
  ibl::PrefilterOptions options;
  options.faceSize = 16;  // 16 and 8 texels over 90 degrees: magnified mips, as on a phone
  options.samples = 16;
  auto env = ibl::prefilterCpu(pano, options);
  EXPECT_TRUE(env.ok()) << (env.ok() ? "" : env.message());
  return env.ok() ? std::move(*env) : uniformEnvironment(glm::vec3(0.0f));
}

// The background alone (the scene's one small ball is behind the camera), looking down -Z.
Image renderBackground(const PackedEnvironment& env, float blur) {
  Scene s;
  s.materials = {lambert(glm::vec3(0.5f))};
  s.meshes.push_back(sphereMesh({0.0f, 0.0f, 5.0f}, 0.1f, 0, 8));
  finishScene(s);
  RenderSettings rs;
  rs.width = kBackgroundWidth;
  rs.height = kBackgroundHeight;
  rs.progressive.frames = 1;
  rs.backgroundBlur = blur;
  auto img = renderRadiance(s, env, lookAtCamera({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 40.0f),
                            rs);
  EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.message());
  return img.ok() ? std::move(*img) : Image(kBackgroundWidth, kBackgroundHeight, 4);
}

// The largest change of slope along the middle row, relative to the largest slope: bilinear
// magnification is piecewise linear, its slope jumps at every texel boundary (about 1 here);
// a B-spline's slope changes smoothly over a texel (about 1 / pixels per texel).
double kinkiness(const Image& image) {
  const int y = image.height / 2;
  std::vector<double> v;
  for (int x = 0; x < image.width; ++x) {
    const float* p = image.pixel(x, y);
    v.push_back((p[0] + p[1] + p[2]) / 3.0);
  }
  double slope = 0.0, kink = 0.0;
  for (size_t i = 0; i + 2 < v.size(); ++i) {
    const double d1 = v[i + 1] - v[i], d2 = v[i + 2] - 2.0 * v[i + 1] + v[i];
    slope = std::max(slope, std::abs(d1));
    kink = std::max(kink, std::abs(d2));
  }
  return slope > 0.0 ? kink / slope : 0.0;
}

TEST_F(BackgroundGLTest, MagnifiedMipsShowNoTexelGrid) {
  const PackedEnvironment env = windowEnvironment();
  for (float blur : {0.1f, 0.3f}) {
    const Image image = renderBackground(env, blur);
    // The window is seen: the row's centre is brighter than its ends.
    const float* centre = image.pixel(kBackgroundWidth / 2, kBackgroundHeight / 2);
    const float* end = image.pixel(2, kBackgroundHeight / 2);
    EXPECT_GT(centre[0], end[0] * 2.0f) << "blur " << blur;
    // 6 to 12 pixels per texel: bilinear measures about 0.7, the B-spline 0.06.
    EXPECT_LT(kinkiness(image), 0.25) << "blur " << blur;
  }
}

TEST_F(BackgroundGLTest, AUniformSkyStaysUniform) {
  const Image image = renderBackground(uniformEnvironment(glm::vec3(0.7f, 0.5f, 0.3f)), 0.5f);
  for (int y = 0; y < image.height; y += 7) {
    for (int x = 0; x < image.width; x += 5) {
      const float* p = image.pixel(x, y);
      ASSERT_NEAR(p[0], 0.7f, 2e-3f) << x << "," << y;
      ASSERT_NEAR(p[1], 0.5f, 2e-3f) << x << "," << y;
      ASSERT_NEAR(p[2], 0.3f, 2e-3f) << x << "," << y;
    }
  }
}

}  // namespace
}  // namespace penumbra::test
