// Accumulation in the lighting pass (RendererOptions::fusedAccumulation): a frame drawn in one
// lighting pass adds its sample to the running mean as it draws, background included, instead
// of writing the frame target for an accumulation pass to add. It changes what a frame costs,
// not the image: the mean must be the separate pass's, bit for bit, over a view where the
// background shows, one where it is hidden, and one whose frames need a second light batch
// (which keeps the separate pass).
#include <gtest/gtest.h>

#include <cstdio>

#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class AccumulationGLTest : public GlFixture {};

// A floor with a box and a glossy sphere under the studio environment, lit by `lights` rect
// lights, seen so that the background fills the top of the image.
Scene openScene(int lights) {
  Scene s;
  Material sphere = lambert(glm::vec3(0.9f, 0.6f, 0.3f));
  sphere.roughnessFactor = 0.3f;
  s.materials = {lambert(glm::vec3(0.7f)), lambert(glm::vec3(0.3f, 0.5f, 0.8f)), sphere};
  s.meshes.push_back(quadMesh(4.0f, 0.0f, 0));
  s.meshes.push_back(boxMesh({-1.0f, 0.0f, -0.8f}, {0.0f, 1.0f, 0.2f}, 1));
  s.meshes.push_back(sphereMesh({0.6f, 0.5f, 0.1f}, 0.5f, 2, 24));
  for (int i = 0; i < lights; ++i) {
    Light rect;
    rect.type = LightType::Rect;
    rect.position = {-0.8f + 0.8f * static_cast<float>(i), 2.0f, 0.6f};
    rect.direction = {0, -1, 0};
    rect.right = {1, 0, 0};
    rect.up = {0, 0, 1};
    rect.width = rect.height = 0.5f;
    rect.intensity = 20.0f;
    s.lights.push_back(rect);
  }
  finishScene(s);
  return s;
}

struct Accumulated {
  Image image;
  int fused = 0;  // frames whose lighting pass accumulated
};

Accumulated render(const Scene& scene, bool fused, bool background, int lightSamples) {
  Accumulated run{Image(80, 48, 4), 0};
  RenderSettings rs;
  rs.width = 80;
  rs.height = 48;
  rs.progressive.frames = 24;
  rs.progressive.directDelay = 0.0f;
  rs.progressive.lightSamples = lightSamples;
  rs.showBackground = background;
  auto env = studioEnvironment();
  EXPECT_TRUE(env.ok());
  auto r = Renderer::create({.fusedAccumulation = fused});
  EXPECT_TRUE(r.ok());
  if (!env.ok() || !r.ok()) return run;
  EXPECT_TRUE((*r)->setSettings(rs).ok());
  EXPECT_TRUE((*r)->setScene(scene).ok());
  EXPECT_TRUE((*r)->setEnvironment(*env).ok());
  (*r)->setCamera(lookAtCamera({0.3f, 1.2f, 4.0f}, {0.0f, 1.0f, 0.0f}, 45.0f));
  while (!(*r)->converged()) {
    auto f = (*r)->step();
    EXPECT_TRUE(f.ok()) << (f.ok() ? "" : f.message());
    if (!f.ok()) return run;
    if ((*r)->lastFrame().fusedAccumulation) ++run.fused;
  }
  auto img = (*r)->readRadiance();
  EXPECT_TRUE(img.ok());
  if (img.ok()) run.image = std::move(*img);
  return run;
}

void expectSameMean(const Scene& scene, bool background, int lightSamples, int expectFused,
                    const char* name) {
  const Accumulated fused = render(scene, true, background, lightSamples);
  const Accumulated separate = render(scene, false, background, lightSamples);
  std::printf("%s: %d of 24 frames accumulated in the lighting pass\n", name, fused.fused);
  EXPECT_EQ(separate.fused, 0);
  EXPECT_EQ(fused.fused, expectFused) << name;
  // Bit for bit: the same arithmetic on the same values, only where it runs differs.
  EXPECT_TRUE(matchesImage(fused.image, separate.image, {.maxAbs = 0.0, .meanAbs = 0.0}, name));
}

TEST_F(AccumulationGLTest, FusedMeanIsTheSeparatePassBitForBit) {
  const Scene one = openScene(1);
  // Frames 2 to 24 have one batch: all of them accumulate as they draw.
  expectSameMean(one, true, 0, 23, "accumulation_fused_background");
  expectSameMean(one, false, 0, 23, "accumulation_fused_no_background");
  // Two lights with 96 samples each over 23 frames: eight or nine a frame, three batches of at
  // most four; the separate pass stays.
  const Scene two = openScene(2);
  expectSameMean(two, true, 96, 0, "accumulation_two_batches");
}

TEST_F(AccumulationGLTest, FusedFramesShowTheScene) {
  // The bit-for-bit comparison above would also pass if both paths drew nothing: the image
  // must show the lit scene and the environment behind it.
  const Accumulated run = render(openScene(1), true, true, 0);
  double lo = 1e9, hi = 0.0;
  for (int y = 0; y < run.image.height; ++y) {
    for (int x = 0; x < run.image.width; ++x) {
      const float* p = run.image.pixel(x, y);
      const double v = (p[0] + p[1] + p[2]) / 3.0;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  EXPECT_GT(hi, 0.2);
  EXPECT_GT(hi - lo, 0.1);
}

}  // namespace
}  // namespace penumbra::test
