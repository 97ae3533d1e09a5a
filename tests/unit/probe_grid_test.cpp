// The probe grid's layout (progressive/probe_grid.h): follows the bounds, scales with them,
// honours overrides, and its capture order visits every probe once per sweep.
#include <gtest/gtest.h>

#include <set>
#include <tuple>

#include "progressive/probe_grid.h"
#include "progressive/probe_relocation.h"

namespace penumbra::progressive {
namespace {

Bounds box(glm::vec3 lo, glm::vec3 hi) {
  Bounds b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

TEST(ProbeGridTest, OuterProbesTheClearanceInsideTheBounds) {
  const ProbeGrid g = placeProbes(box({0, 0, 0}, {8, 2, 4}), 4.0f);
  EXPECT_EQ(g.counts, glm::ivec3(4, 1, 2));
  EXPECT_EQ(g.count(), 8);
  // Four probes along 8: three spacings and a tenth of one at each end.
  EXPECT_FLOAT_EQ(g.spacing.x, 8.0f / 3.2f);
  EXPECT_FLOAT_EQ(g.origin.x, kProbeClearance * g.spacing.x);
  EXPECT_FLOAT_EQ(g.position(3).x, 8.0f - kProbeClearance * g.spacing.x);
  EXPECT_FLOAT_EQ(g.position(g.count() - 1).z, 4.0f - kProbeClearance * g.spacing.z);
  // One probe along an axis sits at the centre.
  EXPECT_FLOAT_EQ(g.origin.y, 1.0f);
  EXPECT_GE(g.columns() * g.rows(), g.count());
}

TEST(ProbeGridTest, AThinSlabGetsALayerOutsideEachFace) {
  // 8 wide, 0.2 deep at density 4 (cells of 2): a tenth of a cell thick (a relief).
  const ProbeGrid g = placeProbes(box({0, 0, -0.15f}, {8, 4, 0.05f}), 4.0f);
  ASSERT_EQ(g.counts.z, 2);
  const float cellSize = 2.0f;
  EXPECT_FLOAT_EQ(g.position(0).z, -0.15f - 0.5f * cellSize);
  EXPECT_FLOAT_EQ(g.position(g.count() - 1).z, 0.05f + 0.5f * cellSize);
  // A fifth of a cell (an object on a wide floor: the dense scene's rock), a third (a row of
  // spheres) or a cell thick: one layer at the centre.
  for (const float depth : {0.4f, 0.7f, 2.0f}) {
    const ProbeGrid one = placeProbes(box({0, 0, 0}, {8, 4, depth}), 4.0f);
    EXPECT_EQ(one.counts.z, 1) << depth;
    EXPECT_FLOAT_EQ(one.origin.z, 0.5f * depth);
  }
}

TEST(ProbeGridTest, LayoutScalesWithTheScene) {
  const ProbeGrid a = placeProbes(box({-1, 0, -1}, {1, 0.5f, 1}), 4.0f);
  const ProbeGrid b = placeProbes(box({-100, 0, -100}, {100, 50, 100}), 4.0f);
  EXPECT_EQ(a.counts, b.counts);
  for (int i = 0; i < a.count(); ++i) {
    EXPECT_NEAR(a.position(i).x * 100.0f, b.position(i).x, 1e-3f);
    EXPECT_NEAR(a.position(i).y * 100.0f, b.position(i).y, 1e-3f);
  }
  EXPECT_NEAR(a.diagonal * 100.0f, b.diagonal, 1e-3f);
}

TEST(ProbeGridTest, OverridesFlatAxesAndLimits) {
  EXPECT_EQ(placeProbes(box({0, 0, 0}, {1, 1, 1}), 4.0f, {2, 3, 5}).counts, glm::ivec3(2, 3, 5));
  // A ground plane alone: one layer of probes, a finite spacing on the flat axis.
  const ProbeGrid flat = placeProbes(box({-5, 0, -5}, {5, 0, 5}), 4.0f);
  EXPECT_EQ(flat.counts.y, 1);
  EXPECT_GT(flat.spacing.y, 0.0f);
  EXPECT_TRUE(placeProbes(Bounds{}, 4.0f).empty());
  EXPECT_LE(placeProbes(box({0, 0, 0}, {1, 1, 1}), 64.0f, {64, 64, 64}).count(), kMaxProbes);
}

TEST(ProbeGridTest, EveryProbeOncePerSweep) {
  const ProbeGrid g = placeProbes(box({0, 0, 0}, {4, 3, 5}), 4.0f);
  const int n = g.count();
  for (int per : {1, 2, 3, 7}) {
    std::multiset<int> seen;
    // Whole sweeps: lcm(n, per) / per captures visit every probe lcm / n times.
    int captures = n;
    for (uint64_t c = 0; c < static_cast<uint64_t>(captures); ++c) {
      const auto probes = probesForCapture(g, c, per);
      EXPECT_EQ(static_cast<int>(probes.size()), std::min(per, n));
      for (int p : probes) seen.insert(p);
    }
    for (int p = 0; p < n; ++p) EXPECT_EQ(static_cast<int>(seen.count(p)), std::min(per, n)) << per;
  }
}

TEST(ProbeGridTest, CapturesTaperAsTheVolumeSettles) {
  // 64 probes, two a frame by default: a sweep every four frames (16 a frame) until every
  // probe has four captures, then one a frame once settled.
  EXPECT_EQ(probeCapturesThisFrame(2, 64, 0.0, 2), 16);
  EXPECT_EQ(probeCapturesThisFrame(2, 64, 1.99, 9), 16);
  EXPECT_EQ(probeCapturesThisFrame(2, 64, 3.99, 17), 16);
  EXPECT_EQ(probeCapturesThisFrame(2, 64, 4.0, 90), 1);
  EXPECT_EQ(probeCapturesThisFrame(6, 128, 5.0, 90), 3);
  // A small volume fills as fast in frames (16 probes: four a frame), a setting above the
  // fill rate wins, and a large one is held to 16 captures a frame.
  EXPECT_EQ(probeCapturesThisFrame(2, 16, 0.0, 2), 4);
  EXPECT_EQ(probeCapturesThisFrame(8, 16, 3.0, 2), 8);
  EXPECT_EQ(probeCapturesThisFrame(2, 4096, 0.0, 2), 16);
  // Never more than the volume holds, never fewer than one before it has settled.
  EXPECT_EQ(probeCapturesThisFrame(2, 1, 0.0, 2), 1);
  EXPECT_EQ(probeCapturesThisFrame(0, 3, 3.0, 2), 1);
  EXPECT_EQ(probeCapturesThisFrame(2, 0, 0.0, 2), 0);
  // Every probe settles within about 16 frames for any volume up to 64 probes.
  for (int count : {1, 5, 16, 27, 64}) {
    double captures = 0.0;
    int frame = 2;
    for (; captures / count < kProbeSettledCaptures; ++frame) {
      captures += probeCapturesThisFrame(2, count, captures / count, frame);
    }
    EXPECT_LE(frame, 18) << count;
  }
  // A small settled volume: at most a sweep per 32 frames, spread evenly (16 probes: every
  // other frame; 6 probes asking for 6 a frame: 6 in 32 frames).
  for (const auto& [count, perFrame, expected] :
       {std::tuple{16, 2, 16}, std::tuple{6, 6, 6}, std::tuple{64, 2, 32}}) {
    int total = 0, most = 0;
    for (int frame = 1; frame <= 32; ++frame) {
      const int n = probeCapturesThisFrame(perFrame, count, 4.0, frame);
      total += n;
      most = std::max(most, n);
    }
    EXPECT_EQ(total, expected) << count;
    EXPECT_LE(most, 1) << count;
  }
}

TEST(ProbeGridTest, CacheRemadeEveryOtherFrameWhileFillingThenAtAFixedInterval) {
  // Simulate a still view of 1024 frames of a 64-probe volume at the default rate.
  const int count = 64;
  double captured = 0.0;
  int last = -1;
  int young = 0, settled = 0;
  for (int frame = 2; frame <= 1024; ++frame) {
    const double mean = captured / count;
    const bool filling = mean < kProbeSettledCaptures;
    if (remakeProbeCache(last < 0 ? -1 : frame - last, mean)) {
      if (last >= 0) {
        EXPECT_EQ(frame - last, filling ? 2 : kProbeCacheInterval) << frame;
      }
      (filling ? young : settled) += 1;
      last = frame;
    } else {
      // Never later than the interval: the image's probe light is the mean of its remakes.
      EXPECT_LT(frame - last, filling ? 2 : kProbeCacheInterval) << frame;
    }
    captured += probeCapturesThisFrame(2, count, mean, frame);
  }
  // Every other frame while filling (about 16 frames), then every kProbeCacheInterval frames.
  EXPECT_GE(young, 6);
  EXPECT_LE(young, 9);
  EXPECT_NEAR(settled, (1024 - 16) / kProbeCacheInterval, 2);
  // A new view remakes at once.
  EXPECT_TRUE(remakeProbeCache(-1, 10.0));
}

}  // namespace
}  // namespace penumbra::progressive
