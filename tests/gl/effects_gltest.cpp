// Post effects (passes/effect_chain.h): bloom spreads an emissive square's light into a halo,
// keeps the displayed image's mean radiance (light is moved, not added), leaves the linear
// read-back (the mean) as it is, and changes nothing when off.
#include <cmath>

#include <gtest/gtest.h>

#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class EffectsGLTest : public GlFixture {};

// sRGB-encoded display value back to linear.
double toLinear(float v) {
  return v <= 0.04045f ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

double meanLinearDisplay(const Image& img) {
  double sum = 0.0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      for (int c = 0; c < 3; ++c) sum += toLinear(img.pixel(x, y)[c]);
    }
  }
  return sum / (3.0 * img.width * img.height);
}

float displayAt(const Image& img, int x, int y) {
  return img.pixel(x, y)[0];
}

TEST_F(EffectsGLTest, BloomSpreadsLightAndKeepsTheMean) {
  // A black floor with a square of radiance 0.8 in the middle, seen from above; no tone curve
  // (the display is linear radiance, sRGB-encoded, nothing clipped).
  Scene s;
  Material glow = lambert(glm::vec3(0.0f));
  glow.emissiveFactor = glm::vec3(0.8f);
  s.materials = {lambert(glm::vec3(0.0f)), glow};
  s.meshes.push_back(quadMesh(4.0f, 0.0f, 0));
  s.meshes.push_back(quadMesh(0.4f, 0.01f, 1));
  finishScene(s);
  RenderSettings rs;
  rs.width = rs.height = 96;
  rs.progressive.frames = 4;
  rs.toneMapper = ToneMapper::None;
  rs.showBackground = false;
  Image display[2], radiance[2];
  for (int on = 0; on < 2; ++on) {
    rs.bloom = on ? 0.5f : 0.0f;
    auto r = Renderer::create();
    ASSERT_TRUE(r.ok());
    ASSERT_TRUE((*r)->setSettings(rs).ok());
    ASSERT_TRUE((*r)->setScene(s).ok());
    ASSERT_TRUE((*r)->setEnvironment(uniformEnvironment(glm::vec3(0.0f))).ok());
    (*r)->setCamera(lookAtCamera({0.0f, 2.0f, 0.001f}, {0.0f, 0.0f, 0.0f}, 60.0f));
    while (!(*r)->converged()) ASSERT_TRUE((*r)->step().ok());
    auto d = (*r)->readDisplay();
    auto l = (*r)->readRadiance();
    ASSERT_TRUE(d.ok() && l.ok());
    display[on] = std::move(*d);
    radiance[on] = std::move(*l);
  }
  EXPECT_EQ(radiance[0].pixels, radiance[1].pixels) << "the linear mean is not an effect's";
  // The square covers the middle ~17 pixels; a pixel 12 pixels beyond its edge is black without
  // bloom and lit with it; the square's centre gives some of its light away.
  const int c = 48;
  std::printf("centre %.3f -> %.3f, halo %.3f -> %.3f, corner %.3f -> %.3f\n",
              displayAt(display[0], c, c), displayAt(display[1], c, c),
              displayAt(display[0], c + 20, c), displayAt(display[1], c + 20, c),
              displayAt(display[0], 2, 2), displayAt(display[1], 2, 2));
  EXPECT_EQ(displayAt(display[0], c + 20, c), 0.0f);
  EXPECT_GT(displayAt(display[1], c + 20, c), 2.0f / 255.0f);
  EXPECT_LT(displayAt(display[1], c, c), displayAt(display[0], c, c));
  EXPECT_LT(displayAt(display[1], 2, 2), displayAt(display[1], c + 20, c)) << "it falls off";
  const double m0 = meanLinearDisplay(display[0]), m1 = meanLinearDisplay(display[1]);
  std::printf("mean linear radiance of the display: %.5f without bloom, %.5f with\n", m0, m1);
  EXPECT_NEAR(m1, m0, 0.05 * m0) << "bloom moves light, it does not add any";
}

}  // namespace
}  // namespace penumbra::test
