// The light-kind table (scene/light_kinds.h): one row per LightType, names that round-trip,
// areas and sample points that agree with each shape.
#include <gtest/gtest.h>

#include <algorithm>

#include "passes/limits.h"
#include "scene/light_kinds.h"

namespace penumbra {
namespace {

TEST(LightKindsTest, EveryTypeHasOneRowWhoseNameFindsIt) {
  ASSERT_EQ(lightKinds().size(), 5u);
  for (const LightKind& k : lightKinds()) {
    EXPECT_EQ(&lightKind(k.type), &k);
    EXPECT_EQ(lightKindNamed(k.name, k.area), &k) << k.name;
    EXPECT_EQ(lightKindNamed(k.name, !k.area), nullptr) << k.name;
  }
  EXPECT_EQ(lightKindNamed("sphere", true), nullptr);
  EXPECT_TRUE(lightKind(LightType::Disk).area);
  EXPECT_FALSE(lightKind(LightType::Spot).area);
  EXPECT_EQ(lightKind(LightType::Point).shadow, ShadowProjection::Cube);
  EXPECT_EQ(lightKind(LightType::Directional).shadow, ShadowProjection::Orthographic);
}

TEST(LightKindsTest, AreasAndSamplePointsFollowTheShape) {
  Light l;
  l.position = {1, 2, 3};
  l.right = {1, 0, 0};
  l.up = {0, 1, 0};
  l.width = 2.0f;
  l.height = 0.5f;
  l.type = LightType::Rect;
  EXPECT_FLOAT_EQ(l.area(), 1.0f);
  EXPECT_TRUE(l.isArea());
  const LightKind& rect = lightKind(LightType::Rect);
  EXPECT_EQ(rect.samplePoint(l, {0.5f, 0.5f}), l.position);
  EXPECT_EQ(rect.samplePoint(l, {1.0f, 1.0f}), glm::vec3(2.0f, 2.25f, 3.0f));  // a corner
  l.type = LightType::Disk;
  EXPECT_NEAR(l.area(), 3.14159265f, 1e-5f);  // width is the diameter
  const glm::vec3 edge = lightKind(LightType::Disk).samplePoint(l, {1.0f, 0.5f});
  EXPECT_NEAR(glm::length(edge - l.position), 1.0f, 1e-5f) << "on the rim";
  l.type = LightType::Spot;
  EXPECT_EQ(l.area(), 0.0f);
  EXPECT_FALSE(l.isArea());
  EXPECT_EQ(lightKind(LightType::Spot).samplePoint(l, {0.9f, 0.1f}), l.position);
}

TEST(LightKindsTest, APunctualDrawsSampleIsItsLightsOrASunOrASkyShadow) {
  Light l;
  for (const LightType t : {LightType::Point, LightType::Spot, LightType::Directional}) {
    l.type = t;
    // A punctual light's shader code is its plain sample's code.
    EXPECT_EQ(static_cast<int>(punctualSample(l, false, false)), lightKind(t).shaderCode);
    EXPECT_EQ(punctualSample(l, false, true), PunctualSample::SkyShadow);
  }
  l.type = LightType::Directional;
  EXPECT_EQ(punctualSample(l, true, false), PunctualSample::Sun);
  l.type = LightType::Spot;
  EXPECT_EQ(punctualSample(l, true, false), PunctualSample::Spot) << "only directional is a sun";
  // Every kind has its own bit, within the key's five.
  uint32_t bits = 0;
  for (const PunctualSampleKind& k : punctualSampleKinds()) {
    EXPECT_EQ(bits & sampleBit(k.sample), 0u) << k.name;
    bits |= sampleBit(k.sample);
  }
  EXPECT_EQ(bits, kAllPunctualSamples);
  EXPECT_LT(kAllPunctualSamples, 32u);
}

TEST(LightKindsTest, EveryShaderGetsEachKindsCodeByName) {
  const gl::Defines d = passes::commonDefines();
  const auto value = [&](const std::string& name) {
    for (const auto& [k, v] : d) {
      if (k == name) return v;
    }
    return std::string("missing");
  };
  EXPECT_EQ(value("PN_LIGHT_DISK"), std::to_string(lightKind(LightType::Disk).shaderCode));
  EXPECT_EQ(value("PN_LIGHT_SPOT"), std::to_string(lightKind(LightType::Spot).shaderCode));
  EXPECT_EQ(value("PN_LIGHT_DIRECTIONAL"), "2");
  // Punctual samples: a code and a PN_PUNCTUAL_KINDS bit each, from one table.
  EXPECT_EQ(value("PN_SAMPLE_SKY_SHADOW"), std::to_string(static_cast<int>(PunctualSample::SkyShadow)));
  EXPECT_EQ(value("PN_KIND_SKY_SHADOW"), std::to_string(sampleBit(PunctualSample::SkyShadow)));
  EXPECT_EQ(value("PN_SAMPLE_SUN"), std::to_string(static_cast<int>(PunctualSample::Sun)));
  EXPECT_EQ(punctualSampleKinds().size(), static_cast<size_t>(PunctualSample::Count));
  // The tone mappers' codes come from the C++ enum, one define each.
  EXPECT_EQ(value("PN_TONEMAP_PBR_NEUTRAL"), std::to_string(static_cast<int>(ToneMapper::PbrNeutral)));
  EXPECT_EQ(value("PN_TONEMAP_ACES"), std::to_string(static_cast<int>(ToneMapper::AcesFitted)));
  EXPECT_EQ(value("PN_TONEMAP_REINHARD"), std::to_string(static_cast<int>(ToneMapper::Reinhard)));
  EXPECT_EQ(value("PN_TONEMAP_NONE"), std::to_string(static_cast<int>(ToneMapper::None)));
  // Every name the settings take is in the list the defines come from.
  for (const char* name : {"pbr-neutral", "neutral", "aces", "reinhard", "none"}) {
    auto t = parseToneMapper(name);
    ASSERT_TRUE(t.ok()) << name;
    EXPECT_NE(std::find(std::begin(kToneMappers), std::end(kToneMappers), *t),
              std::end(kToneMappers))
        << name << ": add it to kToneMappers";
  }
}

}  // namespace
}  // namespace penumbra
