// First light and measured convergence end to end (issue: a lit first picture, a picture that
// knows when it is done): frame 1 of a scene lit by its own lights shows them, frame 1 of a
// scene the environment carries stays environment-only, and an automatic view stops by
// itself with an error estimate that holds against a longer render.
#include <cmath>

#include <gtest/gtest.h>

#include "penumbra/render_job.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class FirstLightGLTest : public GlFixture {};

std::unique_ptr<Renderer> cornell(std::vector<std::pair<std::string, std::string>> settings,
                                  std::optional<EnvironmentSpec> env = std::nullopt) {
  JobRequest req;
  req.scenePath = sourceDir() + "/assets/cornell_box/cornell_box.json";
  settings.insert(settings.end(), {{"width", "48"}, {"height", "48"}, {"shadowMapSize", "256"}});
  req.settings = std::move(settings);
  req.environment = env;
  auto job = RenderJob::load(req);
  EXPECT_TRUE(job.ok()) << (job.ok() ? "" : job.message());
  auto r = Renderer::create();
  EXPECT_TRUE(r.ok());
  if (!job || !r) return nullptr;
  EXPECT_TRUE(job->applyTo(**r).ok());
  return std::move(*r);
}

TEST_F(FirstLightGLTest, FrameOneOfASceneLitByItsOwnLightsShowsThem) {
  // The Cornell box has no environment: before first light its frame 1 was black but for the
  // lamp (about 1 % of the converged mean).
  auto r = cornell({{"frames", "128"}});
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->step().ok());
  EXPECT_GE(r->lastFrame().shadowPasses, 1) << "frame 1 draws the light's shadow";
  auto first = r->readDisplay();
  ASSERT_TRUE(first.ok());
  ASSERT_TRUE(r->preview().ok());  // the moving view's image is lit too
  auto preview = r->readDisplay();
  ASSERT_TRUE(preview.ok());
  r->restart();
  while (!r->converged()) ASSERT_TRUE(r->step().ok());
  auto last = r->readDisplay();
  ASSERT_TRUE(last.ok());
  const double m1 = meanRgb(*first), mp = meanRgb(*preview), mm = meanRgb(*last);
  std::printf("displayed mean: frame 1 %.4f, preview %.4f, frame 128 %.4f\n", m1, mp, mm);
  EXPECT_GE(m1, 0.5 * mm);
  EXPECT_GE(mp, 0.5 * mm);
}

TEST_F(FirstLightGLTest, FrameOneStaysEnvironmentOnlyWhereTheEnvironmentCarriesTheScene) {
  // The same box under a bright uniform sky: the environment gives most of the light, so
  // frame 1 is the paper's cheap environment-only frame.
  auto r = cornell({{"frames", "128"}},
                   EnvironmentSpec{.kind = EnvironmentSpec::Kind::Uniform, .radiance = glm::vec3(20.0f)});
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->step().ok());
  EXPECT_EQ(r->lastFrame().shadowPasses, 0);
}

TEST_F(FirstLightGLTest, AnAutomaticViewStopsWhenItsMeasuredErrorIsReached) {
  // A loose threshold: the view stops early, at a checkpoint, and its estimate holds against
  // the same view carried on to 4x the frames (for noise, I_n - I_4n has 0.87 times the error
  // of I_n; a term that converges more slowly than 1/sqrt(N), such as the probe volume's
  // filling, makes the estimate optimistic: allow twice it).
  auto r = cornell({{"frames", "auto"}, {"maxFrames", "512"}, {"convergenceThreshold", "3"}});
  ASSERT_TRUE(r);
  while (!r->converged()) ASSERT_TRUE(r->step().ok());
  const ConvergenceInfo c = r->convergence();
  std::printf("auto: %d frames, error %.3f, tiles %.3f\n", r->framesDone(), c.error, c.tileError);
  ASSERT_TRUE(c.automatic && c.measured && c.converged);
  const int n = r->framesDone();
  EXPECT_LT(n, 512);
  EXPECT_EQ(n & (n - 1), 0) << "stops at a checkpoint";
  EXPECT_EQ(c.frame, n);
  EXPECT_LT(c.error, 3.0);
  auto stopped = r->readDisplay();
  ASSERT_TRUE(stopped.ok());
  auto ref = cornell({{"frames", "auto"},
                      {"maxFrames", std::to_string(4 * n)},
                      {"convergenceThreshold", "0.125"}});
  while (!ref->converged()) ASSERT_TRUE(ref->step().ok());
  auto longer = ref->readDisplay();
  ASSERT_TRUE(longer.ok());
  const double actual = rmse(*stopped, *longer) * 255.0;
  std::printf("rms against %d frames: %.3f 8-bit steps\n", 4 * n, actual);
  EXPECT_LT(actual, 2.0 * c.error + 0.5);
}

}  // namespace
}  // namespace penumbra::test
