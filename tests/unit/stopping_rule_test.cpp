// The automatic view's stopping rule against the stopping oracle on synthetic image sequences of
// known variance, without GL: the oracle frame is the first from which the image is expected
// within one 8-bit step RMS of its 1024-frame image with 99 % of its 8x8 tiles within three
// (tools/oracle measures the same on real renders). The rule must stop at or after the oracle
// frame and not far after it, and a view with nothing left to converge within 4 frames.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "progressive/controller.h"
#include "progressive/convergence.h"

namespace penumbra::progressive {
namespace {

constexpr int kSize = 128;         // pixels a side
constexpr int kTiles = kSize / 8;  // tiles a side
constexpr int kCap = 1024;

// Each pixel's frames: truth + sigma z, and frame 1 off by `firstBias` (a mean holding it keeps
// a bias that falls as 1/N, as a filling probe volume's does). In 8-bit steps.
struct Sequence {
  std::vector<double> sigma, firstBias;
  uint32_t seed = 1;
};

class SyntheticRenderer : public FrameRenderer {
 public:
  explicit SyntheticRenderer(const Sequence& s)
      : seq_(s), rng_(s.seed), sum_(static_cast<size_t>(kSize * kSize), 0.0) {}

  // The displayed image before its rounding to 8 bits, which the renderer measures (the
  // oracle's images are rounded: oracleFrame).
  std::vector<double> mean() const {
    std::vector<double> m(sum_.size());
    for (size_t i = 0; i < m.size(); ++i) m[i] = sum_[i] / frames_;
    return m;
  }
  Status renderFrame(const FramePlan& plan) override {
    if (plan.frame == 1) std::fill(sum_.begin(), sum_.end(), 0.0);
    std::normal_distribution<double> z(0.0, 1.0);
    for (size_t i = 0; i < sum_.size(); ++i) {
      sum_[i] += seq_.sigma[i] * z(rng_) + (plan.frame == 1 ? seq_.firstBias[i] : 0.0);
    }
    frames_ = plan.frame;
    return {};
  }
  // As Renderer::Impl::measureTiles: the change from the kept checkpoint nearest N/2.
  Result<TileChanges> measureTiles(int frame) override {
    TileChanges c;
    std::vector<int> frames;
    for (const auto& k : kept_) frames.push_back(k.first);
    c.against = comparisonCheckpoint(frame, frames);
    const auto now = mean();
    if (c.against > 0) {
      const auto& before = std::find_if(kept_.begin(), kept_.end(), [&](const auto& k) {
                             return k.first == c.against;
                           })->second;
      for (int ty = 0; ty < kSize / kConvergenceTile; ++ty) {
        for (int tx = 0; tx < kSize / kConvergenceTile; ++tx) {
          double sq = 0.0, largest = 0.0;
          for (int y = 0; y < kConvergenceTile; ++y) {
            for (int x = 0; x < kConvergenceTile; ++x) {
              const size_t i = static_cast<size_t>((ty * kConvergenceTile + y) * kSize +
                                                   tx * kConvergenceTile + x);
              const double d = now[i] - before[i];
              sq += d * d;
              largest = std::max(largest, std::abs(d));
            }
          }
          c.rms.push_back(static_cast<float>(std::sqrt(sq / 64.0)));
          c.max.push_back(static_cast<float>(largest));
        }
      }
    }
    if (kept_.size() == static_cast<size_t>(kKeptCheckpoints)) {
      kept_.erase(std::min_element(kept_.begin(), kept_.end(),
                                   [](const auto& a, const auto& b) { return a.first < b.first; }));
    }
    kept_.emplace_back(frame, now);
    return c;
  }

 private:
  Sequence seq_;
  std::mt19937 rng_;
  std::vector<double> sum_;
  int frames_ = 0;
  std::vector<std::pair<int, std::vector<double>>> kept_;
};

// The oracle frame of a sequence of known variance: the first frame from which the expected
// RMS difference to the kCap-frame image is within one step, and 99 % of the tiles' within
// three. Pixel p of the mean at N differs from that at kCap by noise of variance
// sigma^2 (1/N - 1/kCap) and a bias of firstBias (1/N - 1/kCap); both images are rounded to
// 8-bit steps, which adds 1/6 of a step squared.
int oracleFrame(const Sequence& s) {
  auto ok = [&](int n) {
    const double k = 1.0 / n - 1.0 / kCap;
    std::vector<double> tiles;
    double all = 0.0;
    for (int t = 0; t < kTiles * kTiles; ++t) {
      double sq = 0.0;
      for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) {
          const size_t i =
              static_cast<size_t>(((t / kTiles) * 8 + y) * kSize + (t % kTiles) * 8 + x);
          sq += s.sigma[i] * s.sigma[i] * k + s.firstBias[i] * s.firstBias[i] * k * k + 1.0 / 6.0;
        }
      }
      all += sq;
      tiles.push_back(std::sqrt(sq / 64.0));
    }
    std::sort(tiles.begin(), tiles.end());
    const double p99 = tiles[static_cast<size_t>(std::ceil(0.99 * tiles.size())) - 1];
    return std::sqrt(all / (kSize * kSize)) <= 1.0 && p99 <= 3.0;
  };
  int frame = 1;
  while (frame < kCap && !ok(frame)) ++frame;
  return frame;
}

int stopFrame(const Sequence& s) {
  ProgressiveSettings settings;
  settings.frames = 0;
  settings.maxFrames = kCap;
  settings.skipConvergedTiles = false;
  Controller c(settings);
  SyntheticRenderer r(s);
  while (!c.converged()) EXPECT_TRUE(c.step(r).ok());
  return c.framesDone();
}

Sequence uniform(double sigma, double firstBias = 0.0) {
  return {std::vector<double>(kSize * kSize, sigma), std::vector<double>(kSize * kSize, firstBias)};
}

// On independent frames the change from N/2 estimates the error exactly, and the rule's margin
// for real renders (kChangeMargin: their sequences are not independent, and the change
// understates their error) makes it stop later by about the margin squared for noise, the
// margin for a 1/N bias.
void expectStopNearTheOracle(const Sequence& s, const char* what) {
  const int oracle = oracleFrame(s), stop = stopFrame(s);
  std::printf("%s: oracle %d, stop %d (%.2fx)\n", what, oracle, stop,
              static_cast<double>(stop) / oracle);
  EXPECT_GE(stop, oracle) << what;
  EXPECT_LE(stop, 1.3 * kChangeMargin * kChangeMargin * oracle) << what;
}

TEST(StoppingRuleTest, UniformNoiseStopsNearTheOracle) {
  expectStopNearTheOracle(uniform(16.0), "noise of 16 steps");
  expectStopNearTheOracle(uniform(8.0), "noise of 8 steps");
}

TEST(StoppingRuleTest, ANoisyRegionStopsNearTheOracle) {
  // 95 % of the tiles quiet, a few noisy: the tiles' criterion decides, not the RMS.
  Sequence s = uniform(3.0);
  for (int ty = 0; ty < kTiles; ++ty) {
    for (int tx = 0; tx < kTiles; ++tx) {
      if ((ty * kTiles + tx) % 16 != 5) continue;
      for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x)
          s.sigma[static_cast<size_t>((ty * 8 + y) * kSize + tx * 8 + x)] = 40.0;
      }
    }
  }
  s.seed = 3;
  expectStopNearTheOracle(s, "noisy tiles");
}

TEST(StoppingRuleTest, AFallingBiasStopsNearTheOracle) {
  // Frame 1 off by 200 steps (a first frame without the later terms): the mean's bias falls as
  // 1/N, with a little noise on top.
  Sequence s = uniform(2.0, 200.0);
  s.seed = 5;
  expectStopNearTheOracle(s, "a 1/N bias");
}

TEST(StoppingRuleTest, NothingToConvergeStopsWithinFourFrames) {
  EXPECT_LE(stopFrame(uniform(0.0)), 4);
  EXPECT_LE(oracleFrame(uniform(0.0)), 1);
}

}  // namespace
}  // namespace penumbra::progressive
