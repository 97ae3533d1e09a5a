// ProgramKey (passes/lighting_variant.h): one table of the lighting switches and the material's
// features gives the program key and the #defines, so every switch reaches both, and no two
// variants share a key.
#include <gtest/gtest.h>

#include <set>

#include "passes/lighting_variant.h"

namespace penumbra::passes {
namespace {

std::string defineOf(const ProgramKey& v, const std::string& name) {
  for (const auto& [k, value] : v.defines()) {
    if (k == name) return value;
  }
  return "missing";
}

TEST(LightingVariantTest, EverySwitchReachesTheKeyAndItsDefine) {
  const ProgramKey none;
  EXPECT_EQ(none.key(), (std::array<uint64_t, 2>{}));
  EXPECT_EQ(none.defines().size(), 16u + 11u);  // the lighting switches and the features
  std::set<std::array<uint64_t, 2>> keys = {none.key()};
  // Each switch at its largest value: a key of its own, and its define says that value.
  const auto check = [&](ProgramKey v, const char* define, uint32_t value) {
    EXPECT_TRUE(keys.insert(v.key()).second) << define << " collides with another switch";
    EXPECT_EQ(defineOf(v, define), std::to_string(value)) << define;
  };
  ProgramKey v;
  v = {}, v.occlusion = 1, check(v, "PN_OCCLUSION", 1);
  v = {}, v.transmission = 2, check(v, "PN_TRANSMISSION", 2);
  v = {}, v.punctualKinds = 31, check(v, "PN_PUNCTUAL_KINDS", 31);
  v = {}, v.lightCacheWrite = 4, check(v, "PN_LIGHT_CACHE_WRITE", 4);
  v = {}, v.areaStarts = 15, check(v, "PN_AREA_STARTS", 15);
  v = {}, v.punctualCount = 15, check(v, "PN_PUNCTUAL_COUNT", 15);
  v = {}, v.accumulate = 1, check(v, "PN_ACCUMULATE", 1);
  // The material's features, from the same table.
  v = {}, v.textures = (1u << kTextureSlotCount) - 1, check(v, "PN_TEXTURES", 524287);
  v = {}, v.alphaMode = 2, check(v, "PN_ALPHA_MODE", 2);
  v = {}, v.dispersion = 1, check(v, "PN_DISPERSION", 1);
  v = {}, v.lightCacheable = 1, check(v, "PN_LIGHT_CACHEABLE", 1);
  // Switches combine without disturbing each other.
  ProgramKey both;
  both.occlusion = 1;
  both.dispersion = 1;
  ProgramKey occlusion, dispersion;
  occlusion.occlusion = 1;
  dispersion.dispersion = 1;
  for (size_t w = 0; w < 2; ++w) {
    EXPECT_EQ(both.key()[w], occlusion.key()[w] | dispersion.key()[w]);
  }
}

TEST(LightingVariantTest, EachOutputHasItsOwnProgramFile) {
  LightingVariant v;
  EXPECT_STREQ(v.fragmentFile(), "lighting.frag");
  v.transmission = 1;  // a transmissive surface's own light is a frame's sample
  EXPECT_STREQ(v.fragmentFile(), "lighting.frag");
  v.transmission = 2;
  EXPECT_STREQ(v.fragmentFile(), "transmission_compose.frag");
  v = {}, v.capture = 1;
  EXPECT_STREQ(v.fragmentFile(), "probe_capture.frag");
  v = {}, v.probeCacheWrite = 1;
  EXPECT_STREQ(v.fragmentFile(), "probe_cache.frag");
  v = {}, v.lightCacheWrite = 2;
  EXPECT_STREQ(v.fragmentFile(), "light_cache.frag");
  EXPECT_GE(kProgramKeyFreeBits, 16);
}

TEST(LightingVariantTest, AValueTooWideForItsBitsIsAProgrammingError) {
  ProgramKey v;
  v.areaCount = 8;  // three bits
  EXPECT_DEATH(v.key(), "areaCount does not fit its bits");
  v = {};
  v.alphaMode = 4;  // two bits
  EXPECT_DEATH(v.key(), "alphaMode does not fit its bits");
}

}  // namespace
}  // namespace penumbra::passes
