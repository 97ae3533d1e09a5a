// Scene files: every documented field, defaults, and one-line errors for bad input.
#include <gtest/gtest.h>

#include "penumbra/scene_file.h"
#include "test_support.h"

namespace penumbra {
namespace {

TEST(SceneFileTest, ReadsEveryField) {
  auto sf = parseSceneJson(R"({
    "gltf": "model.glb",
    "environment": {"file": "env/sky.hdr", "intensity": 2.5, "rotation": 90},
    "camera": "front",
    "resolution": [640, 360],
    "exposure": -1.5,
    "toneMapper": "aces",
    "background": {"show": false, "blur": 0.25},
    "progressive": {"frames": 256, "fd": 0.5, "occlusionDistance": 0.75, "lightSamples": 32,
                    "shadowMapSize": 512, "screenSpaceIndirect": false, "indirectClamp": 4, "seed": 7}
  })",
                           "/scenes", "test.json");
  ASSERT_TRUE(sf.ok()) << sf.message();
  EXPECT_EQ(sf->gltfPath, "/scenes/model.glb");
  EXPECT_EQ(sf->environment.kind, EnvironmentSpec::Kind::File);
  EXPECT_EQ(sf->environment.path, "/scenes/env/sky.hdr");
  EXPECT_EQ(sf->camera, "front");
  const RenderSettings& s = sf->settings;
  EXPECT_EQ(s.width, 640);
  EXPECT_EQ(s.height, 360);
  EXPECT_FLOAT_EQ(s.exposure, -1.5f);
  EXPECT_EQ(s.toneMapper, ToneMapper::AcesFitted);
  EXPECT_FLOAT_EQ(s.environmentIntensity, 2.5f);
  EXPECT_FLOAT_EQ(s.environmentRotation, 90.0f);
  EXPECT_FALSE(s.showBackground);
  EXPECT_FLOAT_EQ(s.backgroundBlur, 0.25f);
  EXPECT_EQ(s.progressive.frames, 256);
  EXPECT_FLOAT_EQ(s.progressive.directDelay, 0.5f);
  EXPECT_FLOAT_EQ(s.progressive.occlusionDistance, 0.75f);
  EXPECT_EQ(s.progressive.lightSamples, 32);
  EXPECT_EQ(s.progressive.shadowMapSize, 512);
  EXPECT_FALSE(s.progressive.screenSpaceIndirect);
  EXPECT_FLOAT_EQ(s.progressive.indirectClamp, 4.0f);
  EXPECT_EQ(s.progressive.seed, 7u);
  EXPECT_TRUE(sf->warnings.empty());
}

TEST(SceneFileTest, DefaultsAndUniformEnvironment) {
  auto sf = parseSceneJson(
      R"({"gltf": "a.gltf", "environment": {"uniform": [0.1, 0.2, 0.3]}, "camera": 2})", "",
      "t.json");
  ASSERT_TRUE(sf.ok()) << sf.message();
  EXPECT_EQ(sf->settings, RenderSettings{});
  EXPECT_EQ(sf->environment.kind, EnvironmentSpec::Kind::Uniform);
  EXPECT_FLOAT_EQ(sf->environment.radiance.z, 0.3f);
  EXPECT_EQ(sf->camera, "2");
}

TEST(SceneFileTest, UnknownKeysAreWarnings) {
  auto sf = parseSceneJson(R"({"gltf": "a.gltf", "exposre": 1, "progressive": {"frame": 3}})", "",
                           "t.json");
  ASSERT_TRUE(sf.ok());
  ASSERT_EQ(sf->warnings.size(), 2u);
  EXPECT_NE(sf->warnings[0].find("exposre"), std::string::npos);
}

TEST(SceneFileTest, BadInputIsAOneLineError) {
  struct Case {
    const char* json;
    const char* expect;
  } cases[] = {
      {"{", "not valid JSON"},
      {"[1, 2]", "JSON object"},
      {R"({"exposure": 1})", "'gltf'"},
      {R"({"gltf": 3})", "wrong type"},
      {R"({"gltf": "a", "resolution": [1]})", "resolution"},
      {R"({"gltf": "a", "resolution": [0, 10]})", "resolution"},
      {R"({"gltf": "a", "toneMapper": "filmic"})", "tone mapper"},
      {R"({"gltf": "a", "progressive": {"frames": 0}})", "frames"},
      {R"({"gltf": "a", "progressive": {"frames": 5000}})", "frames"},
      {R"({"gltf": "a", "progressive": {"fd": 1.5}})", "fd"},
      {R"({"gltf": "a", "progressive": {"shadowMapSize": 1000}})", "shadowMapSize"},
      {R"({"gltf": "a", "progressive": {"indirectClamp": -1}})", "indirectClamp"},
      {R"({"gltf": "a", "progressive": {"seed": -1}})", "seed"},
      {R"({"gltf": "a", "progressive": {"frames": 6e127}})", "frames"},
      {R"({"gltf": "a", "progressive": {"frames": 2.5}})", "frames"},
      {R"({"gltf": "a", "exposure": "bright"})", "exposure"},
      {R"({"gltf": "a", "environment": {"rotation": 1000}})", "environmentRotation"},
      {R"({"gltf": "a", "environment": {"preset": "sunset"}})", "preset"},
      {R"({"gltf": "a", "environment": {"file": "x.hdr", "preset": "studio"}})", "one of"},
      {R"({"gltf": "a", "environment": "1,2"})", "environment"},
      {R"({"gltf": "a", "environment": 5})", "environment"},
      {R"({"gltf": "a", "environment": {"uniform": [1, 2]}})", "uniform"},
  };
  for (const auto& c : cases) {
    auto sf = parseSceneJson(c.json, "", "bad.json");
    ASSERT_FALSE(sf.ok()) << c.json;
    EXPECT_NE(sf.message().find(c.expect), std::string::npos) << sf.message();
    EXPECT_EQ(sf.message().find('\n'), std::string::npos);
    EXPECT_EQ(sf.message().rfind("bad.json", 0), 0u) << sf.message();
  }
}

TEST(SceneFileTest, MissingFileAndModelPaths) {
  auto missing = loadSceneFile("/nonexistent/scene.json");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.message().find("/nonexistent/scene.json"), std::string::npos);
  auto model = loadSceneFile(test::sourceDir() + "/assets/cornell_box/cornell_box.gltf");
  ASSERT_TRUE(model.ok()) << model.message();
  EXPECT_EQ(model->settings, RenderSettings{});
  auto bundled = loadSceneFile(test::sourceDir() + "/assets/cornell_box/cornell_box.json");
  ASSERT_TRUE(bundled.ok()) << bundled.message();
  EXPECT_EQ(bundled->camera, "cornell");
}

TEST(SceneFileTest, EnvironmentSpecs) {
  using Kind = EnvironmentSpec::Kind;
  struct Case {
    const char* text;
    Kind kind;
  } cases[] = {{"none", Kind::None},           {"black", Kind::None},
               {"studio", Kind::Studio},       {"default", Kind::Default},
               {"0.1,0.2,0.3", Kind::Uniform}, {"env/sky.hdr", Kind::File}};
  for (const auto& c : cases) {
    auto spec = parseEnvironmentSpec(c.text, "/base");
    ASSERT_TRUE(spec.ok()) << c.text << ": " << spec.message();
    EXPECT_EQ(spec->kind, c.kind) << c.text;
    auto again = parseEnvironmentSpec(environmentSpecText(*spec));
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(again->kind, c.kind) << "round trip of " << c.text;
  }
  EXPECT_EQ(parseEnvironmentSpec("env/sky.hdr", "/base")->path, "/base/env/sky.hdr");
  EXPECT_FLOAT_EQ(parseEnvironmentSpec("0.1,0.2,0.3")->radiance.y, 0.2f);
  for (const char* bad : {"", "1,2", "1,2,-3", "1,2,x", "1,2,3,4", "nan,1,1"}) {
    auto spec = parseEnvironmentSpec(bad);
    EXPECT_FALSE(spec.ok()) << "'" << bad << "' was accepted";
  }
  auto preset = parseSceneJson(
      R"({"gltf": "a", "environment": {"preset": "studio", "intensity": 2}})", "", "t.json");
  ASSERT_TRUE(preset.ok()) << preset.message();
  EXPECT_EQ(preset->environment.kind, Kind::Studio);
  EXPECT_FLOAT_EQ(preset->settings.environmentIntensity, 2.0f);
  auto none = parseSceneJson(R"({"gltf": "a", "environment": "none"})", "", "t.json");
  ASSERT_TRUE(none.ok());
  EXPECT_EQ(none->environment.kind, Kind::None);
  auto unset = parseSceneJson(R"({"gltf": "a"})", "", "t.json");
  EXPECT_EQ(unset->environment.kind, Kind::Default);
}

TEST(SceneFileTest, WrittenSceneFilesReadBackTheSame) {
  SceneFile sf;
  sf.gltfPath = "models/chair.glb";
  sf.camera = "front";
  sf.settings.width = 800;
  sf.settings.height = 600;
  sf.settings.exposure = -1.25f;
  sf.settings.toneMapper = ToneMapper::Reinhard;
  sf.settings.environmentRotation = 45.0f;
  sf.settings.showBackground = false;
  sf.settings.progressive.frames = 64;
  sf.settings.progressive.indirectClamp = 3.5f;
  sf.settings.progressive.seed = 4000000000u;
  for (EnvironmentSpec env :
       {EnvironmentSpec{}, EnvironmentSpec{.kind = EnvironmentSpec::Kind::Studio},
        EnvironmentSpec{.kind = EnvironmentSpec::Kind::None},
        EnvironmentSpec{.kind = EnvironmentSpec::Kind::File, .path = "env/sky.hdr"},
        EnvironmentSpec{.kind = EnvironmentSpec::Kind::Uniform, .radiance = {0.5f, 0.25f, 2.0f}}}) {
    sf.environment = env;
    const std::string text = sceneFileJson(sf);
    auto back = parseSceneJson(text, "", "written.json");
    ASSERT_TRUE(back.ok()) << back.message() << "\n" << text;
    EXPECT_TRUE(back->warnings.empty()) << text;
    EXPECT_EQ(back->settings, sf.settings) << text;
    EXPECT_EQ(back->gltfPath, sf.gltfPath);
    EXPECT_EQ(back->camera, sf.camera);
    EXPECT_EQ(back->environment.kind, env.kind) << text;
    EXPECT_EQ(back->environment.path, env.path);
    EXPECT_EQ(back->environment.radiance, env.radiance);
  }
}

TEST(SettingsTest, ToneMapperNamesRoundTrip) {
  for (auto t :
       {ToneMapper::PbrNeutral, ToneMapper::AcesFitted, ToneMapper::Reinhard, ToneMapper::None}) {
    EXPECT_EQ(*parseToneMapper(toneMapperName(t)), t);
  }
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

TEST(SceneFileTest, ProbeVolumeOverrideRoundTrips) {
  auto sf = parseSceneJson(
      R"({"gltf": "a.gltf", "probeVolume": {"min": [-1, 0, -2], "max": [1, 3, 2],
          "counts": [4, 2, 8]}})",
      "/d", "s.json");
  ASSERT_TRUE(sf.ok()) << sf.message();
  EXPECT_TRUE(sf->probeVolume.hasBox);
  EXPECT_EQ(sf->probeVolume.min, glm::vec3(-1, 0, -2));
  EXPECT_EQ(sf->probeVolume.max, glm::vec3(1, 3, 2));
  EXPECT_EQ(sf->probeVolume.counts, glm::ivec3(4, 2, 8));
  auto back = parseSceneJson(sceneFileJson(*sf), "/d", "s2.json");
  ASSERT_TRUE(back.ok()) << back.message();
  EXPECT_EQ(back->probeVolume.min, sf->probeVolume.min);
  EXPECT_EQ(back->probeVolume.counts, sf->probeVolume.counts);
  // Counts alone keep the automatic box.
  auto counts =
      parseSceneJson(R"({"gltf": "a.gltf", "probeVolume": {"counts": [2, 2, 2]}})", "", "c.json");
  ASSERT_TRUE(counts.ok());
  EXPECT_FALSE(counts->probeVolume.hasBox);
  for (const char* bad :
       {R"({"gltf": "a.gltf", "probeVolume": {"min": [0, 0, 0]}})",
        R"({"gltf": "a.gltf", "probeVolume": {"min": [0, 0, 0], "max": [1, 0, 1]}})",
        R"({"gltf": "a.gltf", "probeVolume": {"counts": [0, 1, 1]}})",
        R"({"gltf": "a.gltf", "probeVolume": {"counts": [1, 1]}})",
        R"({"gltf": "a.gltf", "probeVolume": 3})"}) {
    auto e = parseSceneJson(bad, "", "bad.json");
    ASSERT_FALSE(e.ok()) << bad;
    EXPECT_NE(e.message().find("probeVolume"), std::string::npos) << e.message();
    EXPECT_EQ(e.message().find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace penumbra
