// Measured convergence without GL: the automatic plan's blocks (every light complete at every
// checkpoint), the tile estimator against synthetic images of known noise, the controller's
// stop, and the first-light decision.
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "progressive/controller.h"
#include "progressive/convergence.h"
#include "progressive/distributor.h"
#include "progressive/first_light.h"

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
        std::vector<int> expected;
        for (int c = kFirstBlockFrames; c < cap; c *= 2) expected.push_back(c);
        expected.push_back(cap);
        EXPECT_EQ(checkpoints, expected) << "cap " << cap;
      }
    }
  }
}

TEST(AutoPlanTest, LaterBlocksKeepAddingLightSamples) {
  // Each block's samples grow with its frames, so a checkpoint's estimate has about twice the
  // samples of the one before (a fixed count per block would leave the error at its level).
  ProgressiveSettings s;
  s.frames = 0;
  s.maxFrames = 512;
  const auto plan = distributeSamples(s, someLights(1));
  std::map<int, int> perCheckpoint;
  int count = 0;
  for (const auto& f : plan) {
    count += static_cast<int>(f.lights.size());
    if (f.checkpoint) perCheckpoint[f.frame] = count;
  }
  for (int c = 32; c <= 512; c *= 2) {
    EXPECT_NEAR(perCheckpoint[c], 2 * perCheckpoint[c / 2], 0.1 * perCheckpoint[c])
        << "checkpoint " << c;
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

TEST(ConvergenceTest, PoolingTwoChangesHalvesATilesNoise) {
  // Independent samples of sigma 8 per pixel, tiles of 64 pixels: at N = 256 each tile's change
  // since 128 estimates its error, and so does the change from 64 to 128 (twice its variance).
  // Pooled, the tiles' estimates scatter less about the known error (sigma / sqrt(N), the same
  // for every tile), so their 99th percentile (the view's tile measure) sits closer to it.
  const int w = 256, h = 256, n = 256;
  std::mt19937 rng(9);
  std::normal_distribution<double> noise(0.0, 8.0);
  std::vector<double> quarter, half, full;
  for (int p = 0; p < w * h; ++p) {
    double sum = 0.0;
    for (int i = 1; i <= n; ++i) {
      sum += noise(rng);
      if (i == n / 4) quarter.push_back(sum / i);
      if (i == n / 2) half.push_back(sum / i);
    }
    full.push_back(sum / n);
  }
  const auto now = tileRms(full, half, w, h), before = tileRms(half, quarter, w, h);
  std::vector<float> pooled(now.size());
  for (size_t i = 0; i < now.size(); ++i) pooled[i] = pooledError(now[i], before[i]);
  const double expected = 8.0 / std::sqrt(256.0);
  auto scatter = [&](const std::vector<float>& est) {
    double sq = 0.0;
    for (float e : est) sq += std::pow(e / expected - 1.0, 2);
    return std::sqrt(sq / static_cast<double>(est.size()));
  };
  // Relative scatter about 1 / sqrt(2 * 64) raw, sqrt(1/2) of it pooled.
  EXPECT_LT(scatter(pooled), 0.8 * scatter(now));
  EXPECT_NEAR(summarizeTiles(pooled, 1.0, n).error, expected, 0.05 * expected);
  const double p99Raw = summarizeTiles(now, 1.0, n).tileError;
  const double p99Pooled = summarizeTiles(pooled, 1.0, n).tileError;
  EXPECT_GT(p99Pooled, expected);
  EXPECT_LT(p99Pooled - expected, 0.8 * (p99Raw - expected));
  // An error falling faster (a 1/N bias: the change before is twice this one) is overstated,
  // never understated; with no change before there is nothing to pool.
  EXPECT_NEAR(pooledError(1.0f, 2.0f), std::sqrt(1.5f), 1e-6f);
  EXPECT_EQ(pooledError(1.5f, -1.0f), 1.5f);
  EXPECT_EQ(pooledError(1.5f, NAN), 1.5f);
  EXPECT_TRUE(std::isnan(pooledError(NAN, 1.0f)));
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

TEST(ConvergenceTest, ExpectedFramesFollowTheSquareRootLaw) {
  ConvergenceEstimate e = summarizeTiles(std::vector<float>(100, 2.0f), 1.0, 32);
  // Error 2 at 32 against 1: about 4 x 32 frames.
  EXPECT_EQ(expectedFrames(e, 1.0, 1024), 128);
  EXPECT_EQ(expectedFrames(e, 1.0, 100), 100) << "never past the cap";
  EXPECT_EQ(expectedFrames(ConvergenceEstimate{}, 1.0, 512), 512) << "unmeasured: the cap";
}

// Renders nothing; measures a change that halves at every checkpoint (a 1/N error).
class HalvingRenderer : public FrameRenderer {
 public:
  std::vector<int> measured;
  Status renderFrame(const FramePlan&) override { return {}; }
  Result<TileChanges> measureTiles(int frame) override {
    measured.push_back(frame);
    if (measured.size() == 1) return TileChanges{};
    const float change = static_cast<float>(64.0 / frame);
    return TileChanges{std::vector<float>(64, change), std::vector<float>(64, 2.0f * change)};
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
    if (frame == kFirstBlockFrames) return TileChanges{};
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
  // The rest change by 90 / N: the RMS over the image with the skipped half at its frozen 0.45
  // is under 1 first at 128 (1.26 at 64), and the estimate counts that half at 0.45, not 0.
  EXPECT_EQ(c.framesDone(), 128);
  // (The changing half pools 90/128 with 90/64: sqrt(3/2) times 90/128.)
  const double pooled = 90.0 / 128 * std::sqrt(1.5);
  EXPECT_NEAR(c.estimate().error, std::sqrt((0.45 * 0.45 + pooled * pooled) / 2.0), 1e-6);
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
  // 64 / N < 0.5 first at N = 256.
  EXPECT_EQ(c.framesDone(), 256);
  EXPECT_EQ(r.measured, (std::vector<int>{8, 16, 32, 64, 128, 256}));
  EXPECT_TRUE(c.estimate().converged);
  EXPECT_EQ(c.expectedFrames(), 256);
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
