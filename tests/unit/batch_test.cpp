// Batch rendering's GL-free parts: a job file's line as a request (option names, overrides over
// the command line's, one-line errors that name the line), shards, the results line, and the
// environment cache that lets a batch prefilter each panorama once.
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "penumbra/batch.h"
#include "penumbra/image.h"
#include "test_support.h"

namespace penumbra {
namespace {

using nlohmann::json;

std::string batchAsset(const std::string& rel) {
  return test::sourceDir() + "/assets/" + rel;
}

TEST(BatchTest, LineOptionsOverrideTheCommandLine) {
  JobRequest defaults;
  defaults.settings = {{"exposure", "1"}, {"frames", "64"}};
  defaults.camera = "front";
  auto job = parseBatchJob(
      R"({"scene": "a.gltf", "output": "out/a.png", "size": "64x48", "frames": 8,
          "tonemap": "aces", "no-gi": true, "probesPerFrame": 3, "camera": 1,
          "memory-budget": 64})",
      7, defaults);
  ASSERT_TRUE(job.ok()) << job.message();
  EXPECT_EQ(job->line, 7);
  EXPECT_EQ(job->request.scenePath, "a.gltf");
  EXPECT_EQ(job->output, "out/a.png");
  EXPECT_EQ(job->request.camera, "1");
  EXPECT_EQ(job->request.memoryBudgetBytes, int64_t{64} << 20);
  // Applied in order, the line's values win over the command line's.
  auto s = applySettingOverrides(RenderSettings{}, job->request.settings);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(s->width, 64);
  EXPECT_EQ(s->height, 48);
  EXPECT_EQ(s->progressive.frames, 8);
  EXPECT_FLOAT_EQ(s->exposure, 1.0f);
  EXPECT_EQ(s->toneMapper, ToneMapper::AcesFitted);
  EXPECT_FALSE(s->progressive.probeVolume);  // "no-gi": true, as the --no-gi switch
  EXPECT_EQ(s->progressive.probesPerFrame, 3);
}

TEST(BatchTest, SizeAsAnArrayAndEnvironmentAsText) {
  auto job = parseBatchJob(
      R"({"scene": "a.json", "output": "a.exr", "size": [32, 16], "env": "0.5,0.5,0.5"})", 1, {});
  ASSERT_TRUE(job.ok()) << job.message();
  auto s = applySettingOverrides(RenderSettings{}, job->request.settings);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(s->width, 32);
  EXPECT_EQ(s->height, 16);
  ASSERT_TRUE(job->request.environment.has_value());
  EXPECT_EQ(job->request.environment->kind, EnvironmentSpec::Kind::Uniform);
  EXPECT_FLOAT_EQ(job->request.environment->radiance.g, 0.5f);
}

TEST(BatchTest, BadLinesAreOneLineErrorsNamingTheLine) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"scene": "a.gltf", "output": "a.png")", "line 3: not valid JSON"},
      {R"(["a.gltf", "a.png"])", "line 3: not a JSON object"},
      {R"({"output": "a.png"})", "line 3: no \"scene\""},
      {R"({"scene": "a.gltf"})", "line 3: no \"output\""},
      {R"({"scene": "a.gltf", "output": "a.jpg"})", "line 3: output must end in .png"},
      {R"({"scene": "a.gltf", "output": "a.png", "colour": 1})", "unknown option 'colour'"},
      {R"({"scene": "a.gltf", "output": "a.png", "gl": "egl"})", "give it on the command line"},
      {R"({"scene": "a.gltf", "output": "a.png", "size": "64by48"})", "size must be WxH"},
      {R"({"scene": "a.gltf", "output": "a.png", "size": [64]})", "'size' must be"},
      {R"({"scene": "a.gltf", "output": "a.png", "no-gi": 1})", "'no-gi' must be true or false"},
      {R"({"scene": "a.gltf", "output": "a.png", "frames": {"n": 1}})", "'frames' must be"},
      {R"({"scene": "a.gltf", "output": "a.png", "memory-budget": 0})", "'memory-budget'"},
      {R"({"scene": "a.gltf", "output": "a.png", "env": ""})", "line 3: "},
  };
  for (const auto& [line, fragment] : cases) {
    auto job = parseBatchJob(line, 3, {});
    ASSERT_FALSE(job.ok()) << line;
    EXPECT_NE(job.message().find(fragment), std::string::npos) << job.message();
    EXPECT_EQ(job.message().find('\n'), std::string::npos) << job.message();
  }
}

TEST(BatchTest, ShardsSplitJobsRoundRobin) {
  auto shard = parseShard("1/3");
  ASSERT_TRUE(shard.ok()) << shard.message();
  std::vector<int> jobs;
  for (int k = 0; k < 8; ++k) {
    if (shard->contains(k)) jobs.push_back(k);
  }
  EXPECT_EQ(jobs, (std::vector<int>{1, 4, 7}));
  // Every job in exactly one shard.
  for (int k = 0; k < 20; ++k) {
    int owners = 0;
    for (int i = 0; i < 3; ++i) owners += BatchShard{i, 3}.contains(k) ? 1 : 0;
    EXPECT_EQ(owners, 1) << k;
  }
  for (const char* bad : {"3/2", "0/0", "-1/2", "a/b", "1", "1/2x"}) {
    auto s = parseShard(bad);
    ASSERT_FALSE(s.ok()) << bad;
    EXPECT_NE(s.message().find("--shard must be I/N"), std::string::npos) << s.message();
  }
}

TEST(BatchTest, ResultLinesAreJsonWithWhatEachStatusNeeds) {
  BatchResult ok;
  ok.line = 2;
  ok.scene = "a.gltf";
  ok.output = "a.png";
  ok.status = BatchResult::Status::Ok;
  ok.frames = 24;
  ok.width = 64;
  ok.height = 48;
  ok.automatic = true;
  ok.converged = true;
  ok.errorEstimate = 0.41234;
  ok.renderSeconds = 1.23456;
  ok.warnings = {"a.gltf: KHR_x ignored"};
  const std::string text = batchResultJson(ok);
  EXPECT_EQ(text.find('\n'), std::string::npos);
  const json j = json::parse(text);
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["line"], 2);
  EXPECT_EQ(j["frames"], 24);
  EXPECT_EQ(j["size"], json::array({64, 48}));
  EXPECT_EQ(j["converged"], true);
  EXPECT_DOUBLE_EQ(j["error_estimate"].get<double>(), 0.412);
  EXPECT_DOUBLE_EQ(j["render_seconds"].get<double>(), 1.235);
  EXPECT_EQ(j["warnings"].size(), 1u);
  EXPECT_FALSE(j.contains("error"));

  BatchResult failed;
  failed.line = 5;
  failed.error = "cannot open \xff.gltf";  // invalid UTF-8 in a file name
  const json f = json::parse(batchResultJson(failed));
  EXPECT_EQ(f["status"], "failed");
  EXPECT_NE(f["error"].get<std::string>().find("cannot open"), std::string::npos);
  EXPECT_FALSE(f.contains("frames"));
}

TEST(BatchTest, EnvironmentCacheKeepsTheNewestEntries) {
  EnvironmentCache cache(2);
  for (const char* key : {"a", "b", "c"}) cache.put(key, {uniformEnvironment({1, 1, 1}), key, {}});
  EXPECT_EQ(cache.size(), 2u);
  EXPECT_EQ(cache.find("a"), nullptr);
  ASSERT_NE(cache.find("c"), nullptr);
  EXPECT_EQ(cache.find("c")->name, "c");
  cache.put("b", {uniformEnvironment({2, 2, 2}), "b2", {}});  // replaced, now the newest
  cache.put("d", {uniformEnvironment({1, 1, 1}), "d", {}});
  EXPECT_EQ(cache.find("c"), nullptr);
  ASSERT_NE(cache.find("b"), nullptr);
  EXPECT_EQ(cache.find("b")->name, "b2");
}

TEST(BatchTest, JobsSharingAPanoramaPrefilterItOnce) {
  const std::string dir = test::freshOutputDir("batch/env");
  const std::string pano = dir + "/sky.hdr";
  ASSERT_TRUE(writeImage(pano, Image(32, 16, 3, 0.5f)).ok());
  EnvironmentCache cache;
  JobRequest req;
  req.scenePath = batchAsset("cornell_box/cornell_box.gltf");
  req.environment = EnvironmentSpec{.kind = EnvironmentSpec::Kind::File, .path = pano};
  req.panorama.faceSize = 16;
  req.panorama.samples = 8;
  req.environments = &cache;
  auto first = RenderJob::load(req);
  ASSERT_TRUE(first.ok()) << first.message();
  EXPECT_EQ(cache.size(), 1u);
  req.scenePath = batchAsset("dense/dense.glb");  // another scene, the same panorama
  auto second = RenderJob::load(req);
  ASSERT_TRUE(second.ok()) << second.message();
  EXPECT_EQ(cache.size(), 1u);
  EXPECT_EQ(second->environmentKey, first->environmentKey);
  EXPECT_EQ(second->environment.sh.c[0], first->environment.sh.c[0]);
  EXPECT_EQ(second->environmentName, first->environmentName);
  // Other prefilter options, or a changed file, are another environment.
  req.panorama.samples = 16;
  auto third = RenderJob::load(req);
  ASSERT_TRUE(third.ok()) << third.message();
  EXPECT_NE(third->environmentKey, first->environmentKey);
  EXPECT_EQ(cache.size(), 2u);
  ASSERT_TRUE(writeImage(pano, Image(64, 32, 3, 2.0f)).ok());
  auto changed = RenderJob::load(req);
  ASSERT_TRUE(changed.ok()) << changed.message();
  EXPECT_NE(changed->environmentKey, third->environmentKey);
  EXPECT_GT(changed->environment.sh.c[0].r, 2.0f * third->environment.sh.c[0].r);
}

}  // namespace
}  // namespace penumbra
