// The settings schema: one table from which validation, scene files, CLI flags and the web API
// are derived. Every row is reachable, round-trips through text and JSON, and refuses values
// outside its range with a one-line message naming the key.
#include <cmath>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "penumbra/scene_file.h"
#include "penumbra/settings.h"

namespace penumbra {
namespace {

TEST(SettingsSchemaTest, KeysAndFlagsAreUniqueAndDefaultsAreValid) {
  std::set<std::string> keys, flags;
  const RenderSettings defaults;
  EXPECT_TRUE(validate(defaults).ok());
  for (const SettingInfo& info : settingsSchema()) {
    EXPECT_TRUE(keys.insert(std::string(info.key)).second) << info.key;
    if (!info.flag.empty()) {
      EXPECT_TRUE(flags.insert(std::string(info.flag)).second) << info.flag;
    }
    EXPECT_EQ(findSetting(info.key), &info);
    EXPECT_FALSE(info.help.empty()) << info.key;
    // Each row reads and writes its own field: changing it changes the settings.
    RenderSettings changed = defaults;
    const double other =
        info.type == SettingType::Bool         ? 1.0 - info.get(defaults)
        : info.powerOfTwo                      ? info.get(defaults) * 2.0
        : info.type == SettingType::ToneMapper ? std::fmod(info.get(defaults) + 1.0, 4.0)
        : info.get(defaults) == info.min       ? info.min + 1.0
                                               : info.min + (info.minExclusive ? 1.0 : 0.0);
    ASSERT_TRUE(setSetting(changed, info, other).ok()) << info.key;
    EXPECT_NE(changed, defaults) << info.key << " set to " << other << " changed nothing";
    EXPECT_EQ(info.get(changed), other) << info.key;
  }
  EXPECT_EQ(findSetting("nope"), nullptr);
  EXPECT_NE(findSetting("indirectClamp"), nullptr);  // the key the web API had lost
}

TEST(SettingsSchemaTest, TextRoundTripAndRangeErrors) {
  for (const SettingInfo& info : settingsSchema()) {
    RenderSettings s;
    const std::string text = settingText(s, info);
    RenderSettings back;
    back.progressive.frames = 7;  // anything but the default
    ASSERT_TRUE(setSettingText(back, info, text).ok()) << info.key << " = " << text;
    EXPECT_EQ(info.get(back), info.get(s)) << info.key;
    if (info.type == SettingType::Bool || info.type == SettingType::ToneMapper) continue;
    for (double bad : {info.min - 1.0, info.max + 1.0}) {
      RenderSettings t;
      auto st = setSetting(t, info, bad);
      ASSERT_FALSE(st.ok()) << info.key << " accepted " << bad;
      EXPECT_NE(st.message().find(info.key), std::string::npos) << st.message();
      EXPECT_EQ(st.message().find('\n'), std::string::npos);
    }
  }
  RenderSettings s;
  EXPECT_FALSE(setSettingText(s, *findSetting("frames"), "12abc").ok());
  EXPECT_FALSE(setSettingText(s, *findSetting("frames"), "2.5").ok());
  EXPECT_FALSE(setSettingText(s, *findSetting("shadowMapSize"), "1000").ok());
  EXPECT_FALSE(setSettingText(s, *findSetting("screenSpaceIndirect"), "maybe").ok());
  EXPECT_FALSE(setSettingText(s, *findSetting("exposure"), "nan").ok());
  EXPECT_TRUE(setSettingText(s, *findSetting("toneMapper"), "aces").ok());
  EXPECT_EQ(s.toneMapper, ToneMapper::AcesFitted);
}

TEST(SettingsSchemaTest, JsonMergeTakesEveryKeyAndRefusesUnknownOnes) {
  RenderSettings s;
  auto merged = mergeSettingsJson(
      s, R"({"indirectClamp": 4, "frames": 64, "toneMapper": "none", "showBackground": false,
            "seed": 4000000000})");
  ASSERT_TRUE(merged.ok()) << merged.message();
  EXPECT_FLOAT_EQ(merged->progressive.indirectClamp, 4.0f);
  EXPECT_EQ(merged->progressive.frames, 64);
  EXPECT_EQ(merged->toneMapper, ToneMapper::None);
  EXPECT_FALSE(merged->showBackground);
  EXPECT_EQ(merged->progressive.seed, 4000000000u);
  // What settingsToJson writes, mergeSettingsJson reads back to the same settings.
  auto again = mergeSettingsJson(RenderSettings{}, settingsToJson(*merged));
  ASSERT_TRUE(again.ok()) << again.message();
  EXPECT_EQ(*again, *merged);
  for (const char* bad : {R"({"indirectClmp": 4})", R"({"frames": "many"})", R"({"frames": -1})",
                          R"({"showBackground": 1})", "[1]", "not json"}) {
    auto r = mergeSettingsJson(s, bad);
    EXPECT_FALSE(r.ok()) << bad;
  }
  // frames: "auto" is 0, written back as "auto"; the text form reads the same.
  auto automatic = mergeSettingsJson(s, R"({"frames": "auto", "maxFrames": 256})");
  ASSERT_TRUE(automatic.ok()) << automatic.message();
  EXPECT_EQ(automatic->progressive.frames, 0);
  EXPECT_EQ(planFrames(automatic->progressive), 256);
  EXPECT_NE(settingsToJson(*automatic).find(R"("frames":"auto")"), std::string::npos);
  RenderSettings text;
  ASSERT_TRUE(setSettingText(text, *findSetting("frames"), "64").ok());
  ASSERT_TRUE(setSettingText(text, *findSetting("frames"), "auto").ok());
  EXPECT_EQ(text.progressive.frames, 0);
  EXPECT_EQ(settingText(text, *findSetting("frames")), "auto");
  EXPECT_EQ(settingRange(*findSetting("frames")), "auto or 1..4096");
  // The viewer may not set the size: the canvas does.
  EXPECT_FALSE(mergeSettingsJson(s, R"({"width": 100})", /*viewerOnly=*/true).ok());
  EXPECT_TRUE(mergeSettingsJson(s, R"({"width": 100})").ok());
  const std::string schema = settingsSchemaJson();
  for (const SettingInfo& info : settingsSchema()) {
    std::string quoted(1, '"');
    quoted.append(info.key).push_back('"');
    EXPECT_NE(schema.find(quoted), std::string::npos) << info.key;
  }
}

}  // namespace
}  // namespace penumbra
