// RenderJob, the application layer every program loads scenes through: settings overrides,
// camera choice, the default-environment rule and the memory budget, with one-line errors.
#include <fstream>

#include <gtest/gtest.h>

#include "penumbra/render_job.h"
#include "test_support.h"

namespace penumbra {
namespace {

Status writeTextFile(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  return out ? Status{} : makeError("cannot write " + path);
}

std::string asset(const std::string& rel) {
  return test::sourceDir() + "/assets/" + rel;
}

// Mean radiance of an environment (its first SH coefficient times Y00).
float meanRadiance(const PackedEnvironment& env) {
  const glm::vec3 m = env.sh.c[0] * 0.282095f;
  return (m.r + m.g + m.b) / 3.0f;
}

TEST(RenderJobTest, SceneFileSettingsThenOverrides) {
  JobRequest req;
  req.scenePath = asset("cornell_box/cornell_box.json");
  req.settings = {{"frames", "16"}, {"width", "64"}, {"height", "48"}, {"indirectClamp", "2"}};
  auto job = RenderJob::load(req);
  ASSERT_TRUE(job.ok()) << job.message();
  EXPECT_EQ(job->settings.progressive.frames, 16);
  EXPECT_EQ(job->settings.width, 64);
  EXPECT_FLOAT_EQ(job->settings.progressive.indirectClamp, 2.0f);
  EXPECT_FLOAT_EQ(job->settings.progressive.occlusionDistance, 0.3f);  // from the scene file
  EXPECT_EQ(job->camera.name, "cornell");
  EXPECT_EQ(job->environmentName, "uniform(0, 0, 0)");
}

TEST(RenderJobTest, DefaultEnvironmentFollowsTheLights) {
  // A bare glTF: the Cornell box has its own area light, so the world is black; the dense model
  // has no lights, so it gets the studio (punctual lights alone: the test below).
  JobRequest lit;
  lit.scenePath = asset("cornell_box/cornell_box.gltf");
  auto withLights = RenderJob::load(lit);
  ASSERT_TRUE(withLights.ok()) << withLights.message();
  EXPECT_EQ(withLights->environmentName, "none");
  EXPECT_EQ(meanRadiance(withLights->environment), 0.0f);
  JobRequest unlit;
  unlit.scenePath = asset("dense/dense.glb");
  auto studio = RenderJob::load(unlit);
  ASSERT_TRUE(studio.ok()) << studio.message();
  ASSERT_TRUE(studio->scene.lights.empty());
  EXPECT_EQ(studio->environmentName, "studio");
  EXPECT_GT(meanRadiance(studio->environment), 0.2f);
  EXPECT_LT(meanRadiance(studio->environment), 1.0f);
  // The request wins over the rule and over the scene file.
  lit.environment = EnvironmentSpec{.kind = EnvironmentSpec::Kind::Studio};
  auto forced = RenderJob::load(lit);
  ASSERT_TRUE(forced.ok());
  EXPECT_EQ(forced->environmentName, "studio");
  JobRequest file;
  file.scenePath = asset("cornell_box/cornell_box.json");
  file.environment = EnvironmentSpec{.kind = EnvironmentSpec::Kind::Uniform, .radiance = {1, 1, 1}};
  auto uniform = RenderJob::load(file);
  ASSERT_TRUE(uniform.ok());
  EXPECT_NEAR(meanRadiance(uniform->environment), 1.0f, 1e-3f);
}

TEST(RenderJobTest, WarnsWhenPunctualLightsExceedTheLimit) {
  std::string lights, nodes;
  const int count = kMaxPunctualLights + 2;
  for (int i = 0; i < count; ++i) {
    lights += std::string(i ? "," : "") + R"({"type": "point", "intensity": 1})";
    nodes += std::string(i ? "," : "") + R"({"extensions": {"KHR_lights_punctual": {"light": )" +
             std::to_string(i) + "}}}";
  }
  std::string scene = "[";
  for (int i = 0; i < count; ++i) scene += std::string(i ? "," : "") + std::to_string(i);
  const std::string gltf =
      R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"],
          "extensions": {"KHR_lights_punctual": {"lights": [)" +
      lights + "]}}, \"nodes\": [" + nodes + "], \"scenes\": [{\"nodes\": " + scene +
      "]}], \"scene\": 0}";
  const std::string path = test::outputDir() + "/many_punctual.gltf";
  ASSERT_TRUE(writeTextFile(path, gltf).ok());
  auto job = RenderJob::load({.scenePath = path});
  ASSERT_TRUE(job.ok()) << job.message();
  bool warned = false;
  for (const auto& w : job->warnings) {
    warned = warned || w.find(std::to_string(count) + " punctual lights") != std::string::npos;
  }
  EXPECT_TRUE(warned) << "no warning about " << count << " punctual lights";
  // Punctual lights alone (a product file with a key light, as GlamVelvetSofa carries one
  // directional light) keep the studio, the lights shining on top, as three.js's viewers do.
  EXPECT_EQ(job->environmentName, "studio");
  EXPECT_GT(meanRadiance(job->environment), 0.2f);
}

TEST(RenderJobTest, BadRequestsAreOneLineErrors) {
  struct Case {
    JobRequest req;
    const char* expect;
  } cases[] = {
      {{.scenePath = asset("cornell_box/cornell_box.json"), .camera = "nope"}, "nope"},
      {{.scenePath = asset("cornell_box/cornell_box.json"), .settings = {{"frames", "0"}}},
       "frames"},
      {{.scenePath = asset("cornell_box/cornell_box.json"), .settings = {{"framez", "3"}}},
       "unknown setting 'framez'"},
      {{.scenePath = asset("cornell_box/cornell_box.json"),
        .settings = {{"width", "16384"}, {"height", "16384"}},
        .memoryBudgetBytes = int64_t{64} << 20},
       "over the memory budget of 64 MB"},
      {{.scenePath = asset("cornell_box/cornell_box.json"),
        .environment = EnvironmentSpec{.kind = EnvironmentSpec::Kind::File, .path = "/no/sky.hdr"}},
       "/no/sky.hdr"},
      {{.scenePath = "/no/such/scene.json"}, "/no/such/scene.json"},
  };
  for (const auto& c : cases) {
    auto job = RenderJob::load(c.req);
    ASSERT_FALSE(job.ok()) << c.expect;
    EXPECT_NE(job.message().find(c.expect), std::string::npos) << job.message();
    EXPECT_EQ(job.message().find('\n'), std::string::npos) << job.message();
  }
}

}  // namespace
}  // namespace penumbra
