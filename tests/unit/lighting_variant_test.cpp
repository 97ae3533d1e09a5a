// LightingVariant (passes/lighting_variant.h): one table gives the program key and the
// #defines, so every switch reaches both, and no two variants share a key.
#include <gtest/gtest.h>

#include <set>

#include "passes/lighting_variant.h"

namespace penumbra::passes {
namespace {

std::string defineOf(const LightingVariant& v, const std::string& name) {
  for (const auto& [k, value] : v.defines()) {
    if (k == name) return value;
  }
  return "missing";
}

TEST(LightingVariantTest, EverySwitchReachesTheKeyAndItsDefine) {
  const LightingVariant none;
  EXPECT_EQ(none.key(), 0u);
  EXPECT_EQ(none.defines().size(), 16u);
  std::set<uint32_t> keys = {none.key()};
  // Each switch at its largest value: a key of its own, and its define says that value.
  const auto check = [&](LightingVariant v, const char* define, uint32_t value) {
    EXPECT_TRUE(keys.insert(v.key()).second) << define << " collides with another switch";
    EXPECT_EQ(defineOf(v, define), std::to_string(value)) << define;
  };
  LightingVariant v;
  v = {}, v.occlusion = 1, check(v, "PN_OCCLUSION", 1);
  v = {}, v.transmission = 2, check(v, "PN_TRANSMISSION", 2);
  v = {}, v.punctualKinds = 31, check(v, "PN_PUNCTUAL_KINDS", 31);
  v = {}, v.lightCacheWrite = 4, check(v, "PN_LIGHT_CACHE_WRITE", 4);
  v = {}, v.areaStarts = 15, check(v, "PN_AREA_STARTS", 15);
  v = {}, v.punctualCount = 15, check(v, "PN_PUNCTUAL_COUNT", 15);
  v = {}, v.accumulate = 1, check(v, "PN_ACCUMULATE", 1);
  // Switches combine without disturbing each other.
  LightingVariant both;
  both.occlusion = 1;
  both.accumulate = 1;
  LightingVariant occlusion, accumulate;
  occlusion.occlusion = 1;
  accumulate.accumulate = 1;
  EXPECT_EQ(both.key(), occlusion.key() | accumulate.key());
}

TEST(LightingVariantTest, AValueTooWideForItsBitsIsAProgrammingError) {
  LightingVariant v;
  v.areaCount = 8;  // three bits
  EXPECT_DEATH(v.key(), "areaCount does not fit its bits");
}

}  // namespace
}  // namespace penumbra::passes
