// The frame planner without GL: the order of a frame's steps (the split-frame invariants the
// renderer relies on when it runs a frame band by band), how samples fill the lighting
// batches and shadow-map slots, and how the per-view caches' counters advance.
#include <algorithm>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "progressive/frame_planner.h"

namespace penumbra::progressive {
namespace {

FramePlan framePlan(int frame, std::vector<int> lightsOfSamples, bool occlusion = true) {
  FramePlan p;
  p.frame = frame;
  p.occlusion = occlusion;
  p.renderPrepass = frame == 1;
  for (int l : lightsOfSamples) p.lights.push_back({.light = l});
  return p;
}

FrameScene sceneWith(std::vector<PlannerLight> lights, int bands = 1) {
  FrameScene s;
  s.hasScene = true;
  s.lights = std::move(lights);
  s.bands = bands;
  return s;
}

const PlannerLight kArea{.area = true};
const PlannerLight kSpot{};
const PlannerLight kPoint{.point = true};

size_t firstOf(const FrameSchedule& s, StepKind kind) {
  for (size_t i = 0; i < s.steps.size(); ++i) {
    if (s.steps[i].kind == kind) return i;
  }
  return s.steps.size();
}

// The invariants of any schedule: what every band's lighting reads is complete before it.
void expectOrdered(const FrameSchedule& s, int bands) {
  size_t lastPrepass = 0, occlusion = s.steps.size();
  bool sawLighting = false;
  std::vector<size_t> firstLighting(s.batches.size(), s.steps.size());
  std::vector<size_t> lastShadow(s.batches.size(), 0);
  std::vector<int> lightingBands(s.batches.size(), 0);
  int accumulating = 0;
  for (size_t i = 0; i < s.steps.size(); ++i) {
    const FrameStep& st = s.steps[i];
    switch (st.kind) {
      case StepKind::Prepass:
        EXPECT_FALSE(sawLighting) << "the prepass is complete before any lighting";
        lastPrepass = i;
        break;
      case StepKind::Occlusion:
        occlusion = i;
        EXPECT_GE(i, lastPrepass);
        EXPECT_FALSE(sawLighting);
        break;
      case StepKind::ShadowMap:
      case StepKind::PointShadow:
        lastShadow[static_cast<size_t>(st.batch)] = i;
        // A batch's shadow maps come after the previous batch's bands (slots are reused).
        if (st.batch > 0) {
          EXPECT_EQ(lightingBands[static_cast<size_t>(st.batch - 1)], bands);
        }
        break;
      case StepKind::Lighting: {
        sawLighting = true;
        const size_t b = static_cast<size_t>(st.batch);
        firstLighting[b] = std::min(firstLighting[b], i);
        EXPECT_GT(i, lastShadow[b]) << "a batch's bands follow all its shadow maps";
        EXPECT_EQ(st.band, lightingBands[b]++) << "bands in order";
        accumulating += st.accumulate ? 1 : 0;
        break;
      }
      case StepKind::Compose:
        accumulating += st.accumulate ? 1 : 0;
        for (int n : lightingBands) {
          EXPECT_EQ(n, bands) << "compose after every lighting band";
        }
        break;
      case StepKind::CopyBehind:
        for (int n : lightingBands) {
          EXPECT_EQ(n, bands);
        }
        break;
      case StepKind::ProbeCapture:
        EXPECT_EQ(i + static_cast<size_t>(s.probeCaptures - st.index), s.steps.size())
            << "probe captures are the frame's last steps";
        break;
    }
  }
  for (int n : lightingBands) {
    EXPECT_EQ(n, bands) << "every batch draws every band";
  }
  EXPECT_EQ(accumulating, bands) << "each band accumulates exactly once";
  if (s.occlusion) {
    EXPECT_LT(occlusion, s.steps.size());
  }
}

TEST(FramePlannerTest, BandsAndBatchesKeepTheSplitFrameOrder) {
  // Nine area samples of two lights, a spot and a point light, in four bands: the spot takes
  // the first batch's last slot, so that batch holds three area samples, then 4 + 2.
  FrameScene scene = sceneWith({kArea, kArea, kSpot, kPoint}, 4);
  FramePlan plan = framePlan(5, {0, 1, 0, 1, 0, 1, 0, 1, 0, 2, 3});
  CacheState caches;
  caches.prepassValid = true;
  const FrameSchedule s = planFrame(plan, scene, FrameLimits{}, caches);
  ASSERT_EQ(s.batches.size(), 3u);
  EXPECT_EQ(s.batches[0].size(), 3u);
  EXPECT_EQ(s.batches[1].size(), 4u);
  EXPECT_EQ(s.batches[2].size(), 2u);
  // Within a batch, sorted by light.
  for (const auto& b : s.batches) {
    EXPECT_TRUE(std::is_sorted(b.begin(), b.end(), [&](int x, int y) {
      return plan.lights[static_cast<size_t>(x)].light < plan.lights[static_cast<size_t>(y)].light;
    }));
  }
  ASSERT_EQ(s.punctual.size(), 2u);
  EXPECT_EQ(s.punctual[0].shadowSlot, 3) << "after the first batch's three area samples";
  EXPECT_EQ(s.punctual[1].pointShadow, 0);
  EXPECT_EQ(s.punctual[1].shadowSlot, -1);
  EXPECT_FALSE(s.fused) << "three batches";
  expectOrdered(s, 4);
  // Every area sample appears once; shadow-map streams are distinct.
  std::multiset<int> seen;
  for (const auto& b : s.batches) seen.insert(b.begin(), b.end());
  EXPECT_EQ(seen.size(), 9u);
  std::set<int> streams;
  for (const FrameStep& st : s.steps) {
    if (st.kind == StepKind::ShadowMap) {
      EXPECT_TRUE(streams.insert(st.stream).second);
    }
  }
  EXPECT_EQ(streams.size(), 10u) << "nine area samples and the spot";
}

TEST(FramePlannerTest, OneBatchFusesItsAccumulationUnlessItCannot) {
  FrameScene scene = sceneWith({kArea});
  CacheState caches;
  EXPECT_FALSE(planFrame(framePlan(1, {0}), scene, {}, caches).fused) << "frame 1 is swapped in";
  const FrameSchedule two = planFrame(framePlan(2, {0}), scene, {}, caches);
  EXPECT_TRUE(two.fused);
  expectOrdered(two, 1);
  scene.transmissive = true;
  const FrameSchedule glass = planFrame(framePlan(3, {0}), scene, {}, caches);
  EXPECT_FALSE(glass.fused);
  EXPECT_LT(firstOf(glass, StepKind::CopyBehind), firstOf(glass, StepKind::Compose));
  expectOrdered(glass, 1);
  scene.transmissive = false;
  scene.preview = true;
  EXPECT_FALSE(planFrame(framePlan(3, {0}), scene, {}, caches).fused);
  scene.preview = false;
  EXPECT_FALSE(planFrame(framePlan(3, {0}), scene, {.fusedAccumulation = false}, caches).fused);
}

TEST(FramePlannerTest, ThePrepassIsRedrawnWhenInvalidOrWhenCoverageChanges) {
  FrameScene scene = sceneWith({kArea});
  CacheState caches;
  FramePlan plan = framePlan(3, {0});
  FrameSchedule s = planFrame(plan, scene, {}, caches);
  EXPECT_TRUE(s.drawPrepass) << "no valid prepass yet";
  caches.prepassValid = true;  // (the executor's last prepass band)
  s = planFrame(plan, scene, {}, caches);
  EXPECT_FALSE(s.drawPrepass);
  EXPECT_TRUE(s.occlusion) << "the valid prepass serves";
  scene.blended = true;
  s = planFrame(plan, scene, {}, caches);
  EXPECT_TRUE(s.drawPrepass) << "BLEND coverage differs every frame";
  EXPECT_TRUE(s.cachedLights.empty()) << "nor is the light cache used with BLEND surfaces";
  // No occlusion this frame: no prepass, no rays.
  s = planFrame(framePlan(3, {0}, false), scene, {}, caches);
  EXPECT_FALSE(s.drawPrepass);
  EXPECT_FALSE(s.occlusion);
  EXPECT_EQ(firstOf(s, StepKind::Occlusion), s.steps.size());
}

TEST(FramePlannerTest, TheLightCacheCountsItsFramesAndFrameOneResetsIt) {
  FrameScene scene = sceneWith({kArea, kArea});
  scene.frames = 128;
  CacheState caches;
  int written = 0;
  bool everRead = false;
  for (int f = 1; f <= 128; ++f) {
    const FrameSchedule s = planFrame(framePlan(f, {0, 1}), scene, {}, caches);
    EXPECT_EQ(s.cachedLights, (std::vector<int>{0, 1}));
    EXPECT_EQ(s.clearLightCache, s.writeLightCache && written == 0);
    EXPECT_FALSE(s.readLightCache && s.writeLightCache) << "read only once complete, frame " << f;
    written += s.writeLightCache ? 1 : 0;
    everRead = everRead || s.readLightCache;
    EXPECT_EQ(caches.lightCacheWritten, written);
  }
  EXPECT_GT(written, 0);
  EXPECT_TRUE(everRead);
  planFrame(framePlan(1, {0, 1}), scene, {}, caches);
  EXPECT_LE(caches.lightCacheWritten, 1) << "a new view starts the cache afresh";
  // More area lights than the cache holds: none cached.
  FrameScene many = sceneWith({kArea, kArea, kArea, kArea, kArea});
  EXPECT_TRUE(planFrame(framePlan(2, {0}), many, {}, caches).cachedLights.empty());
}

// The probe volume's per-view cache is written by a frame's lighting, after its occlusion rays:
// those read it only once an earlier frame of the view made it (the frame that first makes it
// traces with the full lookup), and a new view starts without one.
TEST(FramePlannerTest, TheOcclusionRaysReadTheProbeCacheOnlyFromAnEarlierFrame) {
  FrameScene scene = sceneWith({kArea});
  scene.probes = true;
  scene.probeCount = 24;
  scene.probeCaptures = 24;
  scene.probeMeanCaptures = 1.0;
  CacheState caches;
  int madeAt = -1;
  for (int f = 1; f <= 64; ++f) {
    const FrameSchedule s = planFrame(framePlan(f, {0}, f > 1), scene, {}, caches);
    EXPECT_EQ(s.occlusionReadsProbeCache, s.occlusion && madeAt > 0 && madeAt < f) << "frame " << f;
    if (s.writeProbeCache) madeAt = f;
    scene.probeMeanCaptures += 0.25;
  }
  EXPECT_GT(madeAt, 2) << "the cache is remade as the volume fills";
  const FrameSchedule first = planFrame(framePlan(1, {0}, false), scene, {}, caches);
  EXPECT_FALSE(first.occlusionReadsProbeCache);
  const FrameSchedule second = planFrame(framePlan(2, {0}), scene, {}, caches);
  EXPECT_TRUE(second.writeProbeCache) << "a new view makes its cache at its first occlusion frame";
  EXPECT_FALSE(second.occlusionReadsProbeCache);
  EXPECT_TRUE(planFrame(framePlan(3, {0}), scene, {}, caches).occlusionReadsProbeCache);
  FrameLimits noCache;
  noCache.probeCache = false;
  EXPECT_FALSE(planFrame(framePlan(4, {0}), scene, noCache, caches).occlusionReadsProbeCache);
}

TEST(FramePlannerTest, FrameOneLeavesOutLightsThatCanOnlyGiveNaN) {
  PlannerLight broken = kArea;
  broken.finite = false;
  FrameScene scene = sceneWith({kArea, broken});
  CacheState caches;
  FrameSchedule one = planFrame(framePlan(1, {0, 1}), scene, {}, caches);
  ASSERT_EQ(one.batches.size(), 1u);
  EXPECT_EQ(one.batches[0], (std::vector<int>{0}));
  FrameSchedule two = planFrame(framePlan(2, {0, 1}), scene, {}, caches);
  EXPECT_EQ(two.batches[0].size(), 2u) << "later frames keep it (the accumulation guards them)";
  // A sample of a light that does not exist is ignored.
  EXPECT_EQ(planFrame(framePlan(2, {0, 7}), scene, {}, caches).batches[0].size(), 1u);
}

TEST(FramePlannerTest, TheSkyDirectionTakesAPunctualSlotOnFramesWithOcclusion) {
  FrameScene scene = sceneWith({kSpot});
  scene.skyShadows = true;
  CacheState caches;
  FrameSchedule s = planFrame(framePlan(2, {0}), scene, {}, caches);
  ASSERT_EQ(s.punctual.size(), 2u);
  EXPECT_EQ(s.punctual[1].sample, -1);
  EXPECT_EQ(s.punctual[0].shadowSlot, 0);
  EXPECT_EQ(s.punctual[1].shadowSlot, 1);
  EXPECT_EQ(planFrame(framePlan(2, {0}, false), scene, {}, caches).punctual.size(), 1u);
  EXPECT_EQ(planFrame(framePlan(2, {0}), scene, {.punctualLights = 1}, caches).punctual.size(), 1u)
      << "no room left";
}

TEST(FramePlannerTest, ProbeCapturesEndTheFrameAndWaitForTheFirstFrameAfterAReset) {
  FrameScene scene = sceneWith({kArea});
  scene.probes = true;
  scene.probeCount = 24;
  CacheState caches;
  FrameSchedule one = planFrame(framePlan(1, {0}), scene, {}, caches);
  EXPECT_EQ(one.probeCaptures, 0) << "an empty volume: frame 1 comes as fast as without it";
  EXPECT_FALSE(one.probeLookups && !one.occlusion);
  FrameSchedule two = planFrame(framePlan(2, {0}), scene, {}, caches);
  EXPECT_GT(two.probeCaptures, 0);
  EXPECT_EQ(two.steps.back().kind, StepKind::ProbeCapture);
  expectOrdered(two, 1);
  // A young volume keeps filling during frame 1 (a viewer orbiting); a settled one does not.
  scene.probeCaptures = 10;
  scene.probeMeanCaptures = 1.0;
  EXPECT_GT(planFrame(framePlan(1, {0}), scene, {}, caches).probeCaptures, 0);
  scene.probeMeanCaptures = 10.0;
  EXPECT_EQ(planFrame(framePlan(1, {0}), scene, {}, caches).probeCaptures, 0);
}

}  // namespace
}  // namespace penumbra::progressive
