// The progressive scheduler without GL: the sample distributor (Algorithm 1), the sequences
// it draws from, and the controller against a mock renderer.
#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "progressive/controller.h"
#include "progressive/distributor.h"
#include "progressive/sequences.h"

namespace penumbra::progressive {
namespace {

std::vector<LightInfo> lights(int n) {
  std::vector<LightInfo> l;
  for (int i = 0; i < n; ++i) {
    l.push_back({i % 2 ? LightShape::Disk : LightShape::Rect, 1.0f + 0.5f * i});
  }
  return l;
}

TEST(DistributorTest, EveryLightCarriesItsFullEnergyAtFrameM) {
  for (int m : {1, 2, 7, 64, 128, 1000, 4096}) {
    for (int nl : {1, 3, 6}) {
      for (int samples : {0, 1, 5, 64}) {
        ProgressiveSettings s;
        s.frames = m;
        s.lightSamples = samples;
        auto plan = distributeSamples(s, lights(nl));
        ASSERT_EQ(plan.size(), static_cast<size_t>(m));
        std::map<int, double> weight;
        for (const auto& f : plan) {
          for (const auto& ls : f.lights) weight[ls.light] += ls.weight;
        }
        for (int i = 0; i < nl; ++i) {
          EXPECT_NEAR(weight[i], m, 1e-3 * m) << "m " << m << " light " << i << " n " << samples;
        }
      }
    }
  }
}

TEST(DistributorTest, ShadowPassesPerFrameDifferByAtMostOne) {
  for (int m : {16, 100, 128, 333}) {
    for (int nl : {1, 2, 5}) {
      ProgressiveSettings s;
      s.frames = m;
      auto plan = distributeSamples(s, lights(nl));
      const int start = directStartFrame(m, s.directDelay);
      int lo = 1 << 30, hi = 0;
      for (const auto& f : plan) {
        const int n = static_cast<int>(f.lights.size());
        if (f.frame < start) {
          EXPECT_EQ(n, 0) << "frame " << f.frame;
        } else {
          lo = std::min(lo, n);
          hi = std::max(hi, n);
        }
      }
      EXPECT_LE(hi - lo, 1) << "m " << m << " lights " << nl;
    }
  }
}

TEST(DistributorTest, FrameOneIsEnvironmentOnlyAndThePrepassComesAtFrameTwo) {
  ProgressiveSettings s;
  s.frames = 128;
  auto plan = distributeSamples(s, lights(2));
  EXPECT_TRUE(plan[0].lights.empty());
  EXPECT_FALSE(plan[0].occlusion);
  EXPECT_FALSE(plan[0].renderPrepass);
  EXPECT_EQ(plan[0].jitter, glm::vec2(0.0f));
  EXPECT_TRUE(plan[1].renderPrepass);
  EXPECT_TRUE(plan[1].occlusion);
  for (size_t i = 2; i < plan.size(); ++i) EXPECT_FALSE(plan[i].renderPrepass);
  EXPECT_EQ(directStartFrame(128, 0.3f), 38);
  EXPECT_TRUE(plan[36].lights.empty());
  EXPECT_FALSE(plan[37].lights.empty());
}

TEST(DistributorTest, EveryLightSeesJittersCentredOnThePixel) {
  // A light is shaded only on the frames its samples land on, at those frames' jitter: the
  // weighted mean of those jitters is where its light lands in the pixel. It must be the
  // pixel's centre (where the environment's, shaded every frame, lands) for fixed and automatic
  // views, with and without first light, one to three lights and the environment's sun.
  for (int m : {0, 32, 128, 512}) {
    for (bool firstLight : {false, true}) {
      for (int nl : {1, 3}) {
        for (uint32_t seed : {1u, 5u}) {
          ProgressiveSettings s;
          s.frames = m;
          s.seed = seed;
          s.maxFrames = 512;
          auto infos = lights(nl);
          infos.push_back({LightShape::Disk, 1.0f, /*fromFrameOne=*/true});
          const auto plan = distributeSamples(s, infos, firstLight);
          std::vector<glm::dvec2> sum(infos.size(), glm::dvec2(0.0));
          std::vector<double> weight(infos.size(), 0.0);
          for (const auto& f : plan) {
            for (const auto& ls : f.lights) {
              sum[static_cast<size_t>(ls.light)] += double(ls.weight) * glm::dvec2(f.jitter);
              weight[static_cast<size_t>(ls.light)] += ls.weight;
            }
          }
          for (size_t i = 0; i < infos.size(); ++i) {
            ASSERT_GT(weight[i], 0.0);
            const glm::dvec2 mean = sum[i] / weight[i];
            // Measured up to 0.09 pixels (m 32, three lights: a dozen samples each); Halton
            // (2, 3) jitter gave 0.31 for every light with 64 samples over 512 frames.
            EXPECT_LT(glm::length(mean), 0.12)
                << "m " << m << (firstLight ? ", first light" : "") << ", " << nl
                << " lights, light " << i << ", seed " << seed;
          }
        }
      }
    }
  }
}

TEST(DistributorTest, TheEnvironmentsSunShinesFromFrameOne) {
  // The sun taken out of the environment's cube map (fromFrameOne) must not be missing from
  // frame 1, the frame shown while navigating: its centre sample comes first, its samples
  // spread over all m frames with their full energy; the other lights still wait.
  for (int m : {1, 16, 128}) {
    ProgressiveSettings s;
    s.frames = m;
    auto infos = lights(2);
    infos[1].shape = LightShape::Disk;
    infos[1].fromFrameOne = true;
    const auto plan = distributeSamples(s, infos);
    const int start = directStartFrame(m, s.directDelay);
    double sunWeight = 0.0;
    int firstSun = 0, lastSun = 0, firstOther = 0;
    for (const auto& f : plan) {
      for (const auto& ls : f.lights) {
        if (ls.light == 1) {
          sunWeight += ls.weight;
          if (!firstSun) firstSun = f.frame;
          lastSun = f.frame;
        } else if (!firstOther) {
          firstOther = f.frame;
        }
      }
    }
    EXPECT_EQ(firstSun, 1) << "m " << m;
    EXPECT_GE(lastSun, m * 3 / 4) << "m " << m;
    EXPECT_NEAR(sunWeight, m, 1e-3 * m);
    EXPECT_EQ(firstOther, m == 1 ? 1 : start) << "m " << m;
    // Frame 1's sun sample is the disk's centre (the centre-outward order).
    for (const auto& ls : plan[0].lights) {
      if (ls.light == 1) {
        EXPECT_LT(glm::length(ls.point - glm::vec2(0.5f)), 0.25f);
      }
    }
  }
}

TEST(DistributorTest, FirstLightLightsFrameOneAndKeepsTheMean) {
  // Where the scene's own lights carry it, frame 1 evaluates each from its centre with weight
  // 1 (frame 1's mean shows every light at full strength), the rest start at frame 2, and each
  // light still carries its full energy at frame m.
  for (int nl : {1, 3}) {
    ProgressiveSettings s;
    s.frames = 128;
    auto plan = distributeSamples(s, lights(nl), /*firstLight=*/true);
    ASSERT_EQ(plan[0].lights.size(), static_cast<size_t>(nl));
    std::map<int, double> first, total;
    for (const auto& l : plan[0].lights) {
      EXPECT_EQ(l.point, glm::vec2(0.5f));
      EXPECT_TRUE(l.shadowed);
      first[l.light] += l.weight;
    }
    for (const auto& f : plan) {
      for (const auto& l : f.lights) total[l.light] += l.weight;
    }
    for (int i = 0; i < nl; ++i) {
      EXPECT_FLOAT_EQ(first[i], 1.0f);
      EXPECT_NEAR(total[i], 128.0, 1e-3);
    }
    EXPECT_FALSE(plan[1].lights.empty());
  }
  EXPECT_EQ(directStartFrame(128, 0.3f, true), 2);
  EXPECT_EQ(directStartFrame(1, 0.3f, true), 1);
  // Without first light, frame 1 stays environment only (the paper's rule).
  ProgressiveSettings s;
  s.frames = 128;
  EXPECT_TRUE(distributeSamples(s, lights(2)).front().lights.empty());
}

TEST(DistributorTest, SingleFrameEvaluatesEveryLightOnce) {
  ProgressiveSettings s;
  s.frames = 1;
  auto plan = distributeSamples(s, lights(3));
  ASSERT_EQ(plan.size(), 1u);
  ASSERT_EQ(plan[0].lights.size(), 3u);
  for (const auto& l : plan[0].lights) {
    EXPECT_FLOAT_EQ(l.weight, 1.0f);
    EXPECT_EQ(l.point, glm::vec2(0.5f));
  }
}

TEST(DistributorTest, IsDeterministicAndSeeded) {
  ProgressiveSettings s;
  s.frames = 64;
  auto a = distributeSamples(s, lights(2));
  auto b = distributeSamples(s, lights(2));
  s.seed = 12345;
  auto c = distributeSamples(s, lights(2));
  bool anyDifferent = false;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].jitter, b[i].jitter);
    EXPECT_EQ(a[i].sequence, b[i].sequence);
    ASSERT_EQ(a[i].lights.size(), b[i].lights.size());
    for (size_t k = 0; k < a[i].lights.size(); ++k) {
      EXPECT_EQ(a[i].lights[k].point, b[i].lights[k].point);
    }
    anyDifferent |= a[i].jitter != c[i].jitter;
  }
  EXPECT_TRUE(anyDifferent);
}

TEST(SequencesTest, LightSamplesAreOrderedFromTheCentreOutward) {
  for (auto shape : {LightShape::Rect, LightShape::Disk}) {
    auto pts = lightSamplePoints(64, shape, 2.0f, 7);
    ASSERT_EQ(pts.size(), 64u);
    auto dist = [&](glm::vec2 p) {
      return shape == LightShape::Disk ? glm::length(concentricDisk(p))
                                       : glm::length((p - 0.5f) * glm::vec2(2.0f, 1.0f));
    };
    for (size_t i = 1; i < pts.size(); ++i) EXPECT_LE(dist(pts[i - 1]), dist(pts[i]) + 1e-6f);
    for (auto p : pts) {
      EXPECT_GE(p.x, 0.0f);
      EXPECT_LT(p.x, 1.0f);
      EXPECT_GE(p.y, 0.0f);
      EXPECT_LT(p.y, 1.0f);
    }
  }
}

TEST(SequencesTest, LightSamplesAreStratified) {
  // Each of the 8 x 8 strata of x holds exactly n / 8 points (Hammersley rows), and the
  // y coordinates cover the strata evenly too.
  auto pts = lightSamplePoints(64, LightShape::Rect, 1.0f, 3);
  std::vector<int> cx(8), cy(8);
  for (auto p : pts) {
    cx[static_cast<size_t>(p.x * 8)]++;
    cy[static_cast<size_t>(p.y * 8)]++;
  }
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(cx[static_cast<size_t>(i)], 8);
    EXPECT_EQ(cy[static_cast<size_t>(i)], 8);
  }
}

TEST(SequencesTest, ConcentricMappingPreservesAreaAndStaysInTheDisk) {
  // Uniform points in the square map to uniform points in the disk: the fraction inside
  // radius r is r^2.
  const int n = 200;
  int inside = 0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      glm::vec2 d = concentricDisk({(i + 0.5f) / n, (j + 0.5f) / n});
      ASSERT_LE(glm::length(d), 1.0f + 1e-5f);
      inside += glm::length(d) < 0.5f;
    }
  }
  EXPECT_NEAR(inside / double(n * n), 0.25, 0.005);
  EXPECT_EQ(concentricDisk({0.5f, 0.5f}), glm::vec2(0.0f));
}

TEST(SequencesTest, JitterStaysInsideThePixelAndAveragesToZero) {
  glm::vec2 mean(0.0f);
  for (int f = 1; f <= 256; ++f) {
    glm::vec2 j = jitter(f, 1);
    EXPECT_LE(std::abs(j.x), 0.5f);
    EXPECT_LE(std::abs(j.y), 0.5f);
    mean += j;
  }
  mean /= 256.0f;
  EXPECT_NEAR(mean.x, 0.0f, 0.01f);
  EXPECT_NEAR(mean.y, 0.0f, 0.01f);
  EXPECT_FLOAT_EQ(radicalInverse(1, 2), 0.5f);
  EXPECT_FLOAT_EQ(radicalInverse(3, 2), 0.75f);
}

TEST(SequencesTest, JitterStaysCentredAndStratifiedOnEveryKthFrame) {
  // A light's samples land on every k-th frame (k = 2 in an automatic view, 8 for a 512-frame
  // view's sun) or on floor(i s) for fractional s. The jitter of those frames must still
  // average to the pixel centre and cover the pixel: with Halton (2, 3), every second frame's
  // x lay in one half of the pixel, which moved a light's shading a quarter pixel.
  for (double stride : {1.0, 2.0, 3.0, 4.0, 8.0, 16.0, 1.5, 2.5}) {
    for (int start : {2, 17}) {
      const int n = 128;
      glm::dvec2 mean(0.0);
      int cells[4][4] = {};
      for (int i = 0; i < n; ++i) {
        const glm::vec2 j = jitter(start + static_cast<int>(std::floor(i * stride)), 7);
        mean += glm::dvec2(j) / double(n);
        ++cells[std::min(3, static_cast<int>((j.x + 0.5f) * 4))]
               [std::min(3, static_cast<int>((j.y + 0.5f) * 4))];
      }
      EXPECT_LT(std::abs(mean.x), 0.04) << "stride " << stride << ", from frame " << start;
      EXPECT_LT(std::abs(mean.y), 0.04) << "stride " << stride << ", from frame " << start;
      // 8 points a cell expected; Kronecker points give 4 to 11 at every stride here.
      for (const auto& row : cells) {
        for (int c : row) {
          EXPECT_GE(c, 3) << "stride " << stride << ", from frame " << start;
          EXPECT_LE(c, 13) << "stride " << stride << ", from frame " << start;
        }
      }
    }
  }
}

class MockRenderer : public FrameRenderer {
 public:
  MOCK_METHOD(Status, renderFrame, (const FramePlan&), (override));
};

TEST(ControllerTest, DrivesTheRendererFrameByFrameUntilConverged) {
  ProgressiveSettings s;
  s.frames = 5;
  Controller c(s);
  c.setLights(lights(1));
  MockRenderer r;
  std::vector<int> frames;
  EXPECT_CALL(r, renderFrame(::testing::_)).Times(5).WillRepeatedly([&](const FramePlan& p) {
    frames.push_back(p.frame);
    return Status{};
  });
  while (!c.converged()) ASSERT_TRUE(c.step(r).ok());
  EXPECT_EQ(frames, (std::vector<int>{1, 2, 3, 4, 5}));
  EXPECT_EQ(*c.step(r), 0) << "a converged controller renders nothing";
}

TEST(ControllerTest, InvalidationAndChangedSettingsRestartAtFrameOne) {
  ProgressiveSettings s;
  s.frames = 10;
  Controller c(s);
  ::testing::NiceMock<MockRenderer> r;
  ON_CALL(r, renderFrame(::testing::_)).WillByDefault(::testing::Return(Status{}));
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(c.step(r).ok());
  EXPECT_EQ(c.framesDone(), 4);
  c.setSettings(s);  // unchanged: keeps going
  EXPECT_EQ(c.framesDone(), 4);
  c.invalidate();  // camera moved
  EXPECT_EQ(c.framesDone(), 0);
  ASSERT_EQ(*c.step(r), 1);
  s.occlusionDistance = 2.0f;
  c.setSettings(s);
  EXPECT_EQ(c.framesDone(), 0);
  ASSERT_EQ(*c.step(r), 1);
  c.setLights(lights(2));
  EXPECT_EQ(c.framesDone(), 0);
}

TEST(ControllerTest, ARendererErrorStopsTheStepAndIsReturned) {
  Controller c;
  MockRenderer r;
  EXPECT_CALL(r, renderFrame(::testing::_))
      .WillOnce(::testing::Return(Status(makeError("lost context"))));
  auto f = c.step(r);
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.message(), "lost context");
  EXPECT_EQ(c.framesDone(), 0);
}

// A renderer that draws every frame in three parts and records (frame, begin) per call.
class ThreePartRenderer : public FrameRenderer {
 public:
  std::vector<std::pair<int, bool>> calls;
  int left = 0;
  Status renderFrame(const FramePlan& plan) override {
    calls.emplace_back(plan.frame, true);
    return {};
  }
  Result<bool> renderFramePart(const FramePlan& plan, bool begin) override {
    if (begin) left = 3;
    calls.emplace_back(plan.frame, begin);
    return --left == 0;
  }
};

TEST(ControllerTest, AFrameInPartsCountsOnlyWhenItsLastPartIsDone) {
  ProgressiveSettings s;
  s.frames = 3;
  Controller c(s);
  ThreePartRenderer r;
  auto p = c.stepPart(r);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->frame, 1);
  EXPECT_FALSE(p->done);
  EXPECT_TRUE(c.inFrame());
  EXPECT_EQ(c.framesDone(), 0);
  ASSERT_TRUE(c.stepPart(r).ok());
  p = c.stepPart(r);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->frame, 1);
  EXPECT_TRUE(p->done);
  EXPECT_FALSE(c.inFrame());
  EXPECT_EQ(c.framesDone(), 1);
  // Frame 2 part-way, then step() finishes it with its remaining parts.
  ASSERT_TRUE(c.stepPart(r).ok());
  ASSERT_EQ(*c.step(r), 2);
  EXPECT_EQ(c.framesDone(), 2);
  // A restart part-way drops the frame: the next part begins frame 1 again.
  ASSERT_TRUE(c.stepPart(r).ok());
  c.invalidate();
  EXPECT_FALSE(c.inFrame());
  p = c.stepPart(r);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->frame, 1);
  const std::vector<std::pair<int, bool>> expected = {
      {1, true}, {1, false}, {1, false}, {2, true}, {2, false}, {2, false}, {3, true}, {1, true}};
  EXPECT_EQ(r.calls, expected);
  // Whole frames through step() when none is in progress.
  c.invalidate();
  ASSERT_EQ(*c.step(r), 1);
  EXPECT_EQ(r.calls.back(), std::make_pair(1, true));
}

TEST(ControllerTest, AFailedPartDropsTheFrame) {
  Controller c;
  ThreePartRenderer ok;
  ASSERT_TRUE(c.stepPart(ok).ok());
  MockRenderer failing;
  EXPECT_CALL(failing, renderFrame(::testing::_))
      .WillOnce(::testing::Return(Status(makeError("lost context"))));
  auto p = c.stepPart(failing);  // the default renderFramePart draws the whole frame
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.message(), "lost context");
  EXPECT_FALSE(c.inFrame());
  EXPECT_EQ(c.framesDone(), 0);
}

// The early frames' ray filter: full in frame 2 (the first with rays), none in frame 1 and from
// fadeFrames + 1 on, falling in between; the plan carries it; 0 turns it off.
TEST(ProgressivePlan, RayFilterFadesOverTheEarlyFrames) {
  EXPECT_EQ(rayFilterWeight(1, 16), 0.0f);
  EXPECT_EQ(rayFilterWeight(2, 16), 1.0f);
  EXPECT_GT(rayFilterWeight(9, 16), 0.0f);
  EXPECT_LT(rayFilterWeight(9, 16), 1.0f);
  EXPECT_GT(rayFilterWeight(9, 16), rayFilterWeight(10, 16));
  EXPECT_EQ(rayFilterWeight(17, 16), 0.0f);
  EXPECT_EQ(rayFilterWeight(2, 0), 0.0f);
  ProgressiveSettings s;
  s.frames = 32;
  const std::vector<FramePlan> plan = distributeSamples(s, {}, true);
  for (const FramePlan& f : plan)
    EXPECT_EQ(f.rayFilter, rayFilterWeight(f.frame, s.rayFilterFrames));
  EXPECT_EQ(plan[1].rayFilter, 1.0f);
}

}  // namespace
}  // namespace penumbra::progressive
