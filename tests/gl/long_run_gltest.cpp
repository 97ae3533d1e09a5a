// The short version of the long-run stability check (tools/soak/run does 10,000 frames):
// 300 frames of the Cornell box at 32x32 as three restarted 100-frame accumulations, after a
// 64-frame run with a NaN-intensity light. Checks finiteness, flat resident memory after the
// first run, bit-stable images across restarts and 100- vs 50-frame convergence (soak.h).
#include <gtest/gtest.h>

#include "../../tools/soak/soak.h"
#include "gl_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class LongRunGLTest : public GlFixture {};

// AddressSanitizer keeps freed memory in quarantine, so resident memory grows under it by
// design: the flat-memory check is only meaningful in an uninstrumented build.
#if defined(__SANITIZE_ADDRESS__)
constexpr double kMaxGrowthMb = 1e9;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr double kMaxGrowthMb = 1e9;
#else
constexpr double kMaxGrowthMb = 8.0;
#endif
#else
constexpr double kMaxGrowthMb = 8.0;
#endif

TEST_F(LongRunGLTest, ShortSoakIsFiniteFlatAndDeterministic) {
  soak::Options o;
  o.cornellGltf = sourceDir() + "/assets/cornell_box/cornell_box.gltf";
  o.width = o.height = 32;
  o.runFrames = 100;
  o.totalFrames = 300;
  o.sampleEvery = 50;
  o.warmupFrames = 100;
  o.maxGrowthMb = kMaxGrowthMb;
  o.injectFrames = 64;
  o.shadowMapSize = 128;
  o.convergenceTolerance = 0.05;
  o.desktopGl = context().isDesktopGl();
  auto rep = soak::run(o, [](const std::string& m) { std::printf("%s\n", m.c_str()); });
  EXPECT_TRUE(rep.ok()) << rep.failure;
  std::printf("resident %.1f MB -> peak %.1f MB; restart diff %.3g; convergence %.4g / %.4g\n",
              rep.baselineMb, rep.peakMb, rep.restartMaxAbs, rep.convergenceMeanAbs,
              rep.meanRadiance);
}

}  // namespace
}  // namespace penumbra::test
