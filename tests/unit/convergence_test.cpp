// Measured convergence without GL: the automatic plan's blocks (every light complete at every
// checkpoint), the tile estimator against synthetic images of known noise, the controller's
// stop, and the first-light decision.
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "progressive/controller.h"
#include "progressive/convergence.h"
#include "progressive/distributor.h"
#include "progressive/first_light.h"
#include "progressive/sequences.h"

namespace penumbra::progressive {
namespace {

std::vector<LightInfo> someLights(int n) {
  std::vector<LightInfo> l;
  for (int i = 0; i < n; ++i) l.push_back({i % 2 ? LightShape::Disk : LightShape::Rect, 1.5f});
  l.back().fromFrameOne = n > 2;  // an environment's sun among them
  return l;
}

TEST(AutoPlanTest, EveryCheckpointCarriesEveryLightsFullEnergy) {
  for (int cap : {16, 100, 512}) {
    for (int nl : {1, 2, 5}) {
      for (bool firstLight : {false, true}) {
        ProgressiveSettings s;
        s.frames = 0;
        s.maxFrames = cap;
        const auto plan = distributeSamples(s, someLights(nl), firstLight);
        ASSERT_EQ(plan.size(), static_cast<size_t>(cap));
        std::vector<int> checkpoints;
        std::map<int, double> weight;
        for (const auto& f : plan) {
          for (const auto& l : f.lights) weight[l.light] += l.weight;
          if (!f.checkpoint) continue;
          checkpoints.push_back(f.frame);
          for (int i = 0; i < nl; ++i) {
            EXPECT_NEAR(weight[i], f.frame, 1e-3 * f.frame)
                << "cap " << cap << " light " << i << " at checkpoint " << f.frame;
          }
        }
        EXPECT_EQ(checkpoints, autoCheckpoints(cap)) << "cap " << cap;
      }
    }
  }
}

TEST(AutoPlanTest, CheckpointsAreCloseEnoughToStopNearWhereTheViewConverges) {
  const auto c = autoCheckpoints(1024);
  ASSERT_GE(c.size(), 5u);
  EXPECT_EQ(std::vector<int>(c.begin(), c.begin() + 4), (std::vector<int>{2, 4, 6, 8}));
  EXPECT_EQ(c.back(), 1024);
  for (size_t i = 4; i < c.size(); ++i) {
    EXPECT_GT(c[i], c[i - 1]);
    EXPECT_LE(c[i], 1.25 * c[i - 1]) << "a stop within 1.25x of the first converged frame";
  }
  // Not tied to powers of two: 100 is between checkpoints, and a cap of 100 ends the list.
  EXPECT_EQ(std::count(c.begin(), c.end(), 100), 0);
  EXPECT_EQ(autoCheckpoints(100).back(), 100);
  EXPECT_EQ(autoCheckpoints(1), (std::vector<int>{1}));
}

TEST(AutoPlanTest, EachLightsSamplesUpToAnyCheckpointAreAPrefixOfItsSequence) {
  // Stratified at any stopping point: the points a light got up to a checkpoint are the first
  // points of its open-ended sequence, in number proportional to the frames so far.
  ProgressiveSettings s;
  s.frames = 0;
  s.maxFrames = 512;
  const auto lights = someLights(2);
  const auto plan = distributeSamples(s, lights);
  std::vector<std::vector<glm::vec2>> got(2);
  for (const auto& f : plan) {
    for (const auto& l : f.lights) got[static_cast<size_t>(l.light)].push_back(l.point);
    if (!f.checkpoint) continue;
    for (size_t i = 0; i < 2; ++i) {
      // Two shadow-map passes a frame in all from frame 2: one a frame for each of two lights,
      // capped at one every two frames.
      EXPECT_NEAR(static_cast<double>(got[i].size()), 0.5 * (f.frame - 1), 1.0) << f.frame;
      std::vector<glm::vec2> prefix;
      for (uint32_t k = 0; k < got[i].size(); ++k) {
        prefix.push_back(lightSequencePoint(k, lights[i].shape, s.seed + 7919u * i));
      }
      auto less = [](glm::vec2 a, glm::vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); };
      auto sorted = got[i];
      std::sort(sorted.begin(), sorted.end(), less);
      std::sort(prefix.begin(), prefix.end(), less);
      EXPECT_EQ(sorted, prefix) << "light " << i << " at checkpoint " << f.frame;
    }
  }
  // A fixed m is one block: frame m is its only checkpoint.
  s.frames = 64;
  const auto fixed = distributeSamples(s, someLights(1));
  for (const auto& f : fixed) EXPECT_EQ(f.checkpoint, f.frame == 64);
}

// Tiles of 8x8 pixels of a w x h image, RMS of a - b over each, in the estimator's units.
std::vector<float> tileRms(const std::vector<double>& a, const std::vector<double>& b, int w,
                           int h) {
  std::vector<float> out;
  for (int ty = 0; ty < h / kConvergenceTile; ++ty) {
    for (int tx = 0; tx < w / kConvergenceTile; ++tx) {
      double sum = 0.0;
      for (int y = 0; y < kConvergenceTile; ++y) {
        for (int x = 0; x < kConvergenceTile; ++x) {
          const size_t i =
              static_cast<size_t>((ty * kConvergenceTile + y) * w + tx * kConvergenceTile + x);
          sum += (a[i] - b[i]) * (a[i] - b[i]);
        }
      }
      out.push_back(static_cast<float>(std::sqrt(sum / (kConvergenceTile * kConvergenceTile))));
    }
  }
  return out;
}

TEST(ConvergenceTest, TheCheckpointChangeEstimatesTheErrorOfSyntheticNoise) {
  // Every pixel averages independent samples of standard deviation sigma (8-bit steps): the
  // mean of N has error sigma / sqrt(N). The change from N/2 to N must estimate it.
  const int w = 64, h = 64;
  const double sigma = 8.0;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<double> sum(static_cast<size_t>(w * h), 0.0), half;
  for (int n = 1; n <= 256; ++n) {
    for (double& v : sum) v += noise(rng);
    if (n == 128) half = sum;
  }
  std::vector<double> meanN(sum.size()), meanHalf(sum.size()), truth(sum.size(), 0.0);
  for (size_t i = 0; i < sum.size(); ++i) {
    meanN[i] = sum[i] / 256.0;
    meanHalf[i] = half[i] / 128.0;
  }
  const double expected = sigma / std::sqrt(256.0);  // 0.5 steps
  const auto e = summarizeTiles(tileRms(meanN, meanHalf, w, h), 1.0, 256);
  ASSERT_TRUE(e.measured);
  EXPECT_NEAR(e.error, expected, 0.08 * expected);
  // And it agrees with the true error of the image shown at N.
  double trueSq = 0.0;
  for (double v : meanN) trueSq += v * v;
  EXPECT_NEAR(e.error, std::sqrt(trueSq / static_cast<double>(meanN.size())), 0.1 * expected);
  EXPECT_TRUE(e.converged) << "0.5 steps against a threshold of 1";
  EXPECT_FALSE(summarizeTiles(tileRms(meanN, meanHalf, w, h), 0.4, 256).converged);
}

TEST(ConvergenceTest, AChangeFromAnyKeptCheckpointScalesToTheError) {
  // The change from M to N, times sqrt(M / (N - M)), estimates the error at N for any M.
  const int w = 64, h = 64;
  const double sigma = 8.0;
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<double> sum(static_cast<size_t>(w * h), 0.0);
  std::map<int, std::vector<double>> means;
  for (int n = 1; n <= 256; ++n) {
    for (double& v : sum) v += noise(rng);
    if (n == 64 || n == 180 || n == 240 || n == 256) {
      auto& m = means[n];
      for (double v : sum) m.push_back(v / n);
    }
  }
  const double expected = sigma / 16.0;
  for (const int against : {64, 180, 240}) {
    const auto change = tileRms(means[256], means[against], w, h);
    std::vector<float> scaled;
    for (float v : change) scaled.push_back(static_cast<float>(v * changeScale(256, against)));
    EXPECT_NEAR(summarizeTiles(scaled, 1.0, 256).error, expected, 0.1 * expected) << against;
  }
  EXPECT_DOUBLE_EQ(changeScale(256, 128), 1.0);
  EXPECT_DOUBLE_EQ(changeScale(256, 0), 1.0) << "nothing kept: unscaled";
  // The kept checkpoint nearest N/2 in ratio, never N itself, frame 1 or an empty slot.
  const std::vector<int> kept{0, 57, 68, 81, 96};
  EXPECT_EQ(comparisonCheckpoint(114, kept), 57);
  EXPECT_EQ(comparisonCheckpoint(136, kept), 68);
  EXPECT_EQ(comparisonCheckpoint(96, kept), 57) << "not itself";
  EXPECT_EQ(comparisonCheckpoint(4, std::vector<int>{0, 1, 2, 0}), 2);
  EXPECT_EQ(comparisonCheckpoint(2, std::vector<int>{0, 1, 0, 0}), 0) << "frame 1 is not kept";
}

TEST(ConvergenceTest, TheShownErrorAddsTheMarginAndTheRounding) {
  // Two roundings to 8 bits differ by 1/6 of a step squared on average: a view whose estimate
  // is 0 still shows 0.41 steps; a large one is the estimate times the margin.
  EXPECT_NEAR(displayedError(0.0), std::sqrt(1.0 / 6.0), 1e-6);
  EXPECT_NEAR(displayedError(10.0), 10.0 * kChangeMargin, 0.01);
  EXPECT_NEAR(displayedError(1.0), std::sqrt(kChangeMargin * kChangeMargin + 1.0 / 6.0), 1e-6);
  for (double e : {0.05, 0.5, 1.0, 4.0}) EXPECT_NEAR(withoutRounding(displayedError(e)), e, 1e-5);
  EXPECT_TRUE(std::isnan(displayedError(NAN)));
}

TEST(ConvergenceTest, TheDecayRateIsTheSlopeOfTheMeasuresLogarithm) {
  std::vector<TrendPoint> noise, bias, mixed;
  for (int n : {8, 16, 32, 64, 128}) {
    noise.push_back({n, 4.0 / std::sqrt(n)});
    bias.push_back({n, 4.0 / n});
    mixed.push_back({n, 4.0 / std::pow(n, 0.6)});
  }
  EXPECT_NEAR(decayRate(noise), 0.5, 1e-9);
  EXPECT_NEAR(decayRate(bias), 1.0, 1e-9);
  EXPECT_NEAR(decayRate(mixed), 0.6, 1e-9);
  // Fewer than five points: drawn towards the prior (half way with three).
  EXPECT_NEAR(decayRate(std::span(noise).first(3)), 0.5 * (0.5 + kDecayPrior), 1e-9);
  // Clamped; too few or unusable points: the prior.
  EXPECT_EQ(
      decayRate(std::vector<TrendPoint>{{8, 1.0}, {16, 1.0}, {32, 1.0}, {64, 1.0}, {128, 1.0}}),
      0.5);
  EXPECT_EQ(decayRate(std::vector<TrendPoint>{{8, 1.0}}), kDecayPrior);
  EXPECT_EQ(decayRate(std::vector<TrendPoint>{{8, 1.0}, {16, NAN}}), kDecayPrior);
}

TEST(ConvergenceTest, OneNoisyRegionKeepsTheViewGoing) {
  // A quiet image with 2 % of its tiles far off: the RMS alone would pass, the tiles do not.
  std::vector<float> tiles(1000, 0.1f);
  for (int i = 0; i < 20; ++i) tiles[static_cast<size_t>(i * 50)] = 5.0f;
  const auto e = summarizeTiles(tiles, 1.0, 64);
  EXPECT_LT(e.error, 1.0);
  EXPECT_FALSE(e.converged);
  EXPECT_NEAR(e.convergedTiles, 0.98, 1e-9);
  tiles[0] = NAN;  // a broken tile is never converged
  EXPECT_FALSE(summarizeTiles(tiles, 1e9, 64).converged);
}

TEST(ConvergenceTest, ExpectedFramesFollowTheMeasuredRate) {
  // The first checkpoint at or after `frames`.
  const auto all = autoCheckpoints(1 << 20);
  auto at = [&](double frames) {
    return *std::lower_bound(all.begin(), all.end(), std::ceil(frames));
  };
  // A cap so far away that what is left before it is all of the error.
  const int far = 1 << 20;
  ConvergenceEstimate e = summarizeTiles(std::vector<float>(100, 2.0f), 1.0, 32);
  // Error 2 at 32 against 1, falling as noise: (2 / 1)^2 times 32 frames, counted without the
  // 8-bit rounding (which does not fall).
  const double r = withoutRounding(2.0) / withoutRounding(1.0);
  EXPECT_NEAR(r, 2.14, 0.01);
  EXPECT_EQ(expectedFrames(e, 1.0, far), at(32 * r * r));
  EXPECT_LE(expectedFrames(e, 1.0, 100), 100) << "never past the cap";
  // Falling as 1/N: r times 32.
  e.decay = e.tileDecay = 1.0;
  EXPECT_EQ(expectedFrames(e, 1.0, far), at(32 * r));
  // The tiles can be the later: 99 % at 12 against 3 x 1, falling as noise: about 16 x 32.
  e = summarizeTiles(std::vector<float>(100, 0.5f), 1.0, 32);
  e.tileError = 12.0;
  e.converged = false;
  const double t = withoutRounding(12.0) / withoutRounding(3.0);
  EXPECT_EQ(expectedFrames(e, 1.0, far), at(32 * t * t));
  EXPECT_EQ(expectedFrames(ConvergenceEstimate{}, 1.0, 512), 512) << "unmeasured: the cap";
}

TEST(ConvergenceTest, ExpectedFramesCountWhatIsLeftBeforeTheCap) {
  // An estimate that is the error against the image at the cap, sqrt(1 - N / cap) of the
  // noise's: at 64 of 1024 frames, 2 steps. Its stop is the first checkpoint c at which
  // 2 sqrt(64 / c) sqrt(1 - c / 1024) / sqrt(1 - 64 / 1024) is under 1 (without rounding).
  const int cap = 1024;
  ConvergenceEstimate e = summarizeTiles(std::vector<float>(100, 2.0f), 1.0, 64);
  const double v = withoutRounding(2.0), bound = withoutRounding(1.0);
  auto meets = [&](int c) {
    return v * std::sqrt(64.0 / c) * std::sqrt(1.0 - c / 1024.0) / std::sqrt(1.0 - 64.0 / 1024.0) <=
           bound;
  };
  const int expected = expectedFrames(e, 1.0, cap);
  const auto all = autoCheckpoints(cap);
  const auto it = std::find(all.begin(), all.end(), expected);
  ASSERT_NE(it, all.end()) << "a checkpoint";
  EXPECT_TRUE(meets(expected)) << expected;
  EXPECT_FALSE(meets(*(it - 1))) << "the checkpoint before still over";
  // Earlier than the same estimate extrapolated as if the cap were unreachable.
  EXPECT_LT(expected, expectedFrames(e, 1.0, 1 << 20));
}

// Renders nothing; keeps checkpoints as the renderer does and measures the change of an error
// of 64 / N (a 1/N bias) since the kept one comparisonCheckpoint picks.
class HalvingRenderer : public FrameRenderer {
 public:
  std::vector<int> measured;
  std::vector<int> kept = std::vector<int>(kKeptCheckpoints, 0);
  Status renderFrame(const FramePlan&) override { return {}; }
  Result<TileChanges> measureTiles(int frame) override {
    measured.push_back(frame);
    TileChanges c;
    c.against = comparisonCheckpoint(frame, kept);
    *std::min_element(kept.begin(), kept.end()) = frame;
    if (c.against == 0) return c;
    const auto change = static_cast<float>(64.0 / c.against - 64.0 / frame);
    c.rms.assign(64, change);
    c.max.assign(64, 2.0f * change);
    return c;
  }
};

TEST(TileSkipTest, ConvergedTilesAreSkippedFromFrame32AndKeepTheirLastChange) {
  // Four tiles: one quiet, one quiet but with a pixel still jumping, one noisy, one NaN.
  const TileChanges c{{0.2f, 0.2f, 3.0f, NAN}, {0.5f, 2.5f, 9.0f, NAN}};
  TileSkip skip;
  EXPECT_FALSE(skip.update(c, 1.0, 16)) << "not before kSkipFromFrame";
  EXPECT_EQ(skip.skipped(), 0);
  EXPECT_TRUE(skip.update(c, 1.0, 32));
  EXPECT_EQ(skip.mask(), (std::vector<uint8_t>{1, 0, 0, 0}));
  EXPECT_EQ(skip.skipped(), 1);
  // A skipped tile's change is zero from now on; its frozen change stands in for it.
  const std::vector<float> later{0.0f, 0.1f, 2.0f, 1.0f};
  EXPECT_EQ(skip.effective(later), (std::vector<float>{0.2f, 0.1f, 2.0f, 1.0f}));
  // Nothing new: no update. Then the second tile quietens and joins; the first stays skipped.
  EXPECT_FALSE(skip.update({{0.0f, 0.3f, 3.0f, 1.0f}, {0.0f, 2.5f, 9.0f, 1.0f}}, 1.0, 64));
  EXPECT_TRUE(skip.update({{0.0f, 0.3f, 3.0f, 1.0f}, {0.0f, 1.0f, 9.0f, 1.0f}}, 1.0, 128));
  EXPECT_EQ(skip.mask(), (std::vector<uint8_t>{1, 1, 0, 0}));
  EXPECT_EQ(skip.effective(std::vector<float>(4, 0.0f)), (std::vector<float>{0.2f, 0.3f, 0, 0}));
  // The bound scales with the threshold.
  TileSkip loose;
  EXPECT_TRUE(loose.update(c, 8.0, 32));
  EXPECT_EQ(loose.mask(), (std::vector<uint8_t>{1, 1, 1, 0}));
  skip.reset();
  EXPECT_TRUE(skip.mask().empty());
}

// Half the tiles are quiet from frame 32; the rest halve their change at every checkpoint.
class HalfQuietRenderer : public FrameRenderer {
 public:
  std::vector<std::vector<uint8_t>> masks;
  Status renderFrame(const FramePlan&) override { return {}; }
  Result<TileChanges> measureTiles(int frame) override {
    if (frame == 2) return TileChanges{};
    TileChanges c;
    for (int i = 0; i < 64; ++i) {
      const bool quiet = i % 2 == 0 && frame >= 32;
      const bool skipped = !masks.empty() && masks.back()[static_cast<size_t>(i)];
      const float v = skipped ? 0.0f : quiet ? 0.45f : static_cast<float>(90.0 / frame);
      c.rms.push_back(v);
      c.max.push_back(2.0f * v);
    }
    return c;
  }
  Status skipTiles(std::span<const uint8_t> mask) override {
    masks.emplace_back(mask.begin(), mask.end());
    return {};
  }
};

TEST(TileSkipTest, TheControllerSkipsConvergedTilesAndCountsThemAtTheirLastChange) {
  ProgressiveSettings s;
  s.frames = 0;
  s.convergenceThreshold = 1.0f;
  Controller c(s);
  HalfQuietRenderer r;
  while (!c.converged()) ASSERT_TRUE(c.step(r).ok());
  ASSERT_EQ(r.masks.size(), 1u) << "the quiet half, once";
  for (size_t i = 0; i < 64; ++i) EXPECT_EQ(r.masks[0][i], i % 2 == 0 ? 1 : 0) << i;
  EXPECT_DOUBLE_EQ(c.estimate().skippedTiles, 0.5);
  // The rest change by 90 / N. The view stops once the RMS over the image is under 1, which
  // counts the skipped half at its frozen 0.45, not 0: (0.45^2 + p^2) / 2 < 1 for the changing
  // half's p, so at least 0.45 / sqrt(2).
  EXPECT_GT(c.framesDone(), 34);
  EXPECT_TRUE(c.estimate().converged);
  EXPECT_GT(c.estimate().error, 0.45 / std::sqrt(2.0));
  EXPECT_LT(c.estimate().error, 1.0);
  // Off: no mask is ever asked for; a restart forgets the mask.
  EXPECT_EQ(c.skippedTiles().skipped(), 32);
  c.invalidate();
  EXPECT_EQ(c.skippedTiles().skipped(), 0);
  s.skipConvergedTiles = false;
  c.setSettings(s);
  r.masks.clear();
  while (!c.converged()) ASSERT_TRUE(c.step(r).ok());
  EXPECT_TRUE(r.masks.empty());
}

TEST(ConvergenceTest, AnAutomaticViewStopsAtTheCheckpointThatConverges) {
  ProgressiveSettings s;
  s.frames = 0;
  s.maxFrames = 1024;
  s.convergenceThreshold = 0.5f;
  Controller c(s);
  HalvingRenderer r;
  while (!c.converged()) ASSERT_TRUE(c.step(r).ok());
  // 64 / N < 0.5 from N = 128 on. The rule counts what is left of it to change before the cap
  // (sqrt(1 - N/1024) of it, as for noise), the margin and the 8-bit rounding: it stops at the
  // first checkpoint where sqrt((1.2 * 64 / N * sqrt(1 - N / 1024))^2 + 1/6) < 0.5.
  const auto all = autoCheckpoints(1024);
  size_t k = 0;
  while (displayedError(64.0 / all[k] * std::sqrt(1.0 - all[k] / 1024.0)) >= 0.5) ++k;
  EXPECT_EQ(c.framesDone(), all[k]);
  EXPECT_EQ(r.measured, std::vector<int>(all.begin(), all.begin() + static_cast<long>(k) + 1))
      << "every checkpoint measured";
  EXPECT_TRUE(c.estimate().converged);
  EXPECT_NEAR(c.estimate().decay, 1.0, 0.05) << "a 1/N error measured as one";
  EXPECT_EQ(c.expectedFrames(), c.framesDone());
  // A restart measures afresh; a fixed m never measures and runs exactly m frames.
  c.invalidate();
  EXPECT_FALSE(c.estimate().measured);
  s.frames = 40;
  c.setSettings(s);
  r.measured.clear();
  while (!c.converged()) ASSERT_TRUE(c.step(r).ok());
  EXPECT_EQ(c.framesDone(), 40);
  EXPECT_TRUE(r.measured.empty());
}

TEST(FirstLightTest, TheEnvironmentsShareDecidesFrameOne) {
  Bounds room;
  room.extend(glm::vec3(-1.0f));
  room.extend(glm::vec3(1.0f));
  Light panel;
  panel.type = LightType::Rect;
  panel.intensity = 10.0f;
  panel.width = panel.height = 0.5f;
  panel.position = {0.0f, 0.9f, 0.0f};
  EXPECT_EQ(environmentShare({panel}, 0.0f, room), 0.0f) << "black environment";
  EXPECT_EQ(environmentShare({}, 1.0f, room), 1.0f) << "no lights";
  // The panel gives L A / r^2 = 10 * 0.25 / 3 at the room's radius, sqrt(3).
  const float own = 10.0f * 0.25f / 3.0f;
  const float env = own / 3.14159265f;  // an environment giving as much
  EXPECT_NEAR(environmentShare({panel}, env, room), 0.5f, 1e-4f);
  // Scene units do not matter: the same room in centimetres.
  Bounds cm;
  cm.extend(glm::vec3(-100.0f));
  cm.extend(glm::vec3(100.0f));
  Light big = panel;
  big.width = big.height = 50.0f;
  big.position *= 100.0f;
  EXPECT_NEAR(environmentShare({big}, env, cm), 0.5f, 1e-4f);
  // A sun of 3 lux against an environment of radiance 1: pi / (pi + 3).
  Light sun;
  sun.type = LightType::Directional;
  sun.intensity = 3.0f;
  EXPECT_NEAR(environmentShare({sun}, 1.0f, room), 3.14159265f / (3.14159265f + 3.0f), 1e-5f);
}

}  // namespace
}  // namespace penumbra::progressive
