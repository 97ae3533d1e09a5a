// The area lights' per-view cache: its schedule (progressive/light_cache.h) and which materials
// it serves (gpu/gpu_scene.h materialFeatures).
#include <gtest/gtest.h>

#include "gpu/gpu_scene.h"
#include "progressive/light_cache.h"

namespace penumbra {
namespace {

TEST(LightCacheScheduleTest, AQuarterOfTheFramesFromFrameTwoThenRead) {
  EXPECT_EQ(progressive::lightCacheFrames(128), 32);
  EXPECT_EQ(progressive::lightCacheFrames(64), 16);
  EXPECT_EQ(progressive::lightCacheFrames(32), 8);
  EXPECT_EQ(progressive::lightCacheFrames(8), 4);      // at least 4 positions
  EXPECT_EQ(progressive::lightCacheFrames(4096), 32);  // at most 32
  for (const int m : {1, 8, 31, 32, 48, 128, 1024}) {
    int written = 0, firstRead = 0;
    for (int frame = 1; frame <= m; ++frame) {
      if (progressive::lightCacheReady(written, m) && firstRead == 0) firstRead = frame;
      if (progressive::writesLightCache(frame, written, m)) {
        EXPECT_GE(frame, 2) << "frame 1 stays a plain forward pass";
        EXPECT_FALSE(progressive::lightCacheReady(written, m)) << "read only once complete";
        ++written;
      }
    }
    const int k = progressive::lightCacheFrames(m);
    if (m < progressive::kLightCacheMinFrames) {
      EXPECT_EQ(written, 0) << "a short view does without it: m " << m;
      EXPECT_EQ(firstRead, 0);
      continue;
    }
    EXPECT_EQ(written, std::min(k, m - 1)) << "m " << m;
    // Read from the frame after its last write, if the view has one.
    if (m > k + 1) {
      EXPECT_EQ(firstRead, k + 2) << "m " << m;
    }
  }
}

bool cacheable(const Material& m, bool metallicRoughnessTexture = false) {
  bool has[kTextureSlotCount] = {};
  has[1] = metallicRoughnessTexture;
  return materialFeatures(m, has).lightCacheable != 0;
}

TEST(LightCacheScheduleTest, SmoothLobesEvaluateTheirLightsEveryFrame) {
  Material rough;
  rough.roughnessFactor = 0.6f;
  EXPECT_TRUE(cacheable(rough));
  Material chrome = rough;
  chrome.metallicFactor = 1.0f;
  chrome.roughnessFactor = 0.08f;  // a light's reflection under a pixel
  EXPECT_FALSE(cacheable(chrome));
  // Unknown roughness per texel: not cached.
  EXPECT_FALSE(cacheable(rough, true));
  Material coated = rough;
  coated.clearcoat = 1.0f;
  coated.clearcoatRoughness = 0.05f;
  EXPECT_FALSE(cacheable(coated));
  coated.clearcoatRoughness = 0.5f;
  EXPECT_TRUE(cacheable(coated));
}

}  // namespace
}  // namespace penumbra
