// A frame drawn in parts (Renderer::stepPart with setFrameTiles) gives the same image as the
// same frame drawn whole: the area-light scene with two light batches, occlusion and
// screen-space indirect light; BLEND and MASK materials (frame 1 alpha-blends, every frame
// redraws the prepass); spot, directional and point lights. Until its last part a frame is not
// counted and the image read back is the previous complete frame's; a restart drops a frame in
// progress, and step() finishes one.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "penumbra/environment.h"
#include "penumbra/render_job.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class FrameSplitGLTest : public GlFixture {};

struct Job {
  Scene scene;
  PackedEnvironment env;
  Camera camera;
  RenderSettings settings;
};

Job loadAsset(const std::string& file, int width, int height, int frames,
              std::vector<std::pair<std::string, std::string>> extra = {}) {
  JobRequest req;
  req.scenePath = sourceDir() + "/assets/" + file;
  req.settings = {{"width", std::to_string(width)},
                  {"height", std::to_string(height)},
                  {"frames", std::to_string(frames)},
                  {"shadowMapSize", "256"}};
  req.settings.insert(req.settings.end(), extra.begin(), extra.end());
  auto job = RenderJob::load(req);
  EXPECT_TRUE(job.ok()) << (job.ok() ? "" : job.message());
  if (!job) return {};
  return {std::move(job->scene), std::move(job->environment), job->camera, job->settings};
}

std::unique_ptr<Renderer> makeRenderer(const Job& j) {
  auto r = Renderer::create();
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.message());
  if (!r) return nullptr;
  EXPECT_TRUE((*r)->setSettings(j.settings).ok());
  EXPECT_TRUE((*r)->setScene(j.scene).ok());
  EXPECT_TRUE((*r)->setEnvironment(j.env).ok());
  (*r)->setCamera(j.camera);
  return std::move(*r);
}

// The largest |a - b| over every channel of every pixel.
float maxDifference(const Image& a, const Image& b) {
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  float worst = 0.0f;
  for (size_t i = 0; i < std::min(a.pixels.size(), b.pixels.size()); ++i) {
    worst = std::max(worst, std::abs(a.pixels[i] - b.pixels[i]));
  }
  return worst;
}

// Renders every frame whole, and again in `tiles` bands part by part; after each frame the
// running means must agree (bit for bit on one GPU; 1e-6 allows for nothing else).
void expectSplitMatchesWhole(const Job& job, int tiles, const char* what) {
  auto whole = makeRenderer(job);
  auto split = makeRenderer(job);
  ASSERT_TRUE(whole && split);
  split->setFrameTiles(tiles);
  int frames = 0, maxParts = 0;
  while (!whole->converged()) {
    auto f = whole->step();
    ASSERT_TRUE(f.ok()) << f.message();
    FramePart p;
    int parts = 0;
    do {
      auto r = split->stepPart();
      ASSERT_TRUE(r.ok()) << r.message();
      p = *r;
      ++parts;
      ASSERT_EQ(p.frame, *f) << what;
      ASSERT_EQ(p.part, parts) << what;
    } while (!p.done);
    EXPECT_EQ(p.parts, parts) << what;
    // Each pass over the image runs once per band: at least lighting (+ accumulation).
    EXPECT_GE(parts, tiles) << what << ", frame " << *f;
    maxParts = std::max(maxParts, parts);
    auto a = whole->readRadiance(), b = split->readRadiance();
    ASSERT_TRUE(a.ok() && b.ok());
    ASSERT_LE(maxDifference(*a, *b), 1e-6f) << what << ", frame " << *f;
    ++frames;
  }
  EXPECT_EQ(frames, job.settings.progressive.frames);
  EXPECT_TRUE(split->converged());
  // Frames with shadow maps and a prepass have more parts than the bands.
  EXPECT_GT(maxParts, tiles) << what;
}

TEST_F(FrameSplitGLTest, AreaLightFramesWithTwoBatchesMatchTheWholeFrame) {
  // Six samples a frame: two batches of shadow maps. Seven bands do not divide 48 rows.
  Job j =
      loadAsset("cornell_box/cornell_box.json", 40, 48, 10, {{"lightSamples", "6"}, {"fd", "0.2"}});
  expectSplitMatchesWhole(j, 7, "cornell");
}

TEST_F(FrameSplitGLTest, BlendAndMaskFramesMatchTheWholeFrame) {
  Job j = loadAsset("glass/glass.json", 64, 36, 6, {{"fd", "0.3"}});
  expectSplitMatchesWhole(j, 4, "glass");
}

TEST_F(FrameSplitGLTest, TransmissiveFramesMatchTheWholeFrame) {
  // Glass looks through a copy of the whole frame, made after every band's lighting: a ray
  // refracted into another band sees that band's light of the same frame.
  Job j = loadAsset("showroom/showroom.json", 48, 32, 6, {{"fd", "0.3"}});
  expectSplitMatchesWhole(j, 3, "showroom");
}

TEST_F(FrameSplitGLTest, PunctualLightFramesMatchTheWholeFrame) {
  Scene s;
  s.materials = {lambert(glm::vec3(0.8f)), lambert(glm::vec3(0.5f))};
  s.meshes.push_back(quadMesh(5.0f, 0.0f, 0));
  s.meshes.push_back(boxMesh({-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}, 1));
  finishScene(s);
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(1, -1, 0));
  sun.intensity = 2.0f;
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {-2, 3, 1};
  spot.direction = glm::normalize(glm::vec3(2, -3, -1));
  spot.intensity = 20.0f;
  Light bulb;
  bulb.type = LightType::Point;
  bulb.position = {1, 2, 2};
  bulb.intensity = 5.0f;
  s.lights = {sun, spot, bulb};
  Job j{std::move(s),
        uniformEnvironment(glm::vec3(0.1f)),
        lookAtCamera({0.0f, 5.0f, 4.0f}, {0.0f, 0.0f, 0.0f}, 40.0f),
        {}};
  j.settings.width = 48;
  j.settings.height = 40;
  j.settings.progressive.frames = 6;
  j.settings.progressive.directDelay = 0.0f;
  j.settings.progressive.shadowMapSize = 256;
  expectSplitMatchesWhole(j, 3, "punctual");
}

TEST_F(FrameSplitGLTest, AFrameInProgressShowsThePreviousMeanAndARestartDropsIt) {
  Job j = loadAsset("cornell_box/cornell_box.json", 32, 32, 8);
  auto r = makeRenderer(j);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->step().ok());
  ASSERT_TRUE(r->step().ok());
  auto mean2 = r->readRadiance();
  ASSERT_TRUE(mean2.ok());
  r->setFrameTiles(4);
  EXPECT_EQ(r->frameTiles(), 4);
  auto p = r->stepPart();
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->frame, 3);
  EXPECT_FALSE(p->done);
  // A new tile count waits for the next frame: this one keeps its parts.
  r->setFrameTiles(2);
  const int parts = p->parts;
  for (int i = 0; i < 2; ++i) {
    p = r->stepPart();
    ASSERT_TRUE(p.ok() && !p->done);
    EXPECT_EQ(p->parts, parts);
  }
  EXPECT_EQ(r->framesDone(), 2) << "not counted before its last part";
  auto mid = r->readRadiance();
  ASSERT_TRUE(mid.ok());
  EXPECT_EQ(mid->pixels, mean2->pixels) << "the image is the last complete frame's";
  // step() finishes the frame in progress: frame 3, as drawn whole.
  auto f = r->step();
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(*f, 3);
  // Its parts: one per shadow map, 4 bands of each pass over the image, one for the occlusion
  // rays (a quarter-resolution pass, whole), one per probe capture.
  const FrameStats& st = r->lastFrame();
  EXPECT_GT(st.probeCaptures, 0);
  EXPECT_TRUE(st.occlusion);
  EXPECT_EQ(parts, st.shadowPasses + 4 * (st.prepass ? 2 : 1) + 1 + st.probeCaptures);
  auto whole = makeRenderer(j);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(whole->step().ok());
  EXPECT_LE(maxDifference(*r->readRadiance(), *whole->readRadiance()), 1e-6f);
  // The next frame has 2 bands; a camera change part-way drops it and restarts at frame 1.
  // The probe volume keeps the captures of frames 1 to 3 (a camera change keeps it) but not
  // those of the dropped frame (its captures are its last parts): as if frame 4 never began.
  p = r->stepPart();
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->frame, 4);
  EXPECT_FALSE(p->done);
  r->setCamera(j.camera);
  p = r->stepPart();
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->frame, 1);
  EXPECT_EQ(p->part, 1);
  while (!r->converged()) ASSERT_TRUE(r->stepPart().ok());
  whole->setCamera(j.camera);
  while (!whole->converged()) ASSERT_TRUE(whole->step().ok());
  EXPECT_LE(maxDifference(*r->readRadiance(), *whole->readRadiance()), 1e-6f);
  auto done = r->stepPart();
  ASSERT_TRUE(done.ok());
  EXPECT_EQ(done->frame, 0) << "converged: nothing to draw";
  EXPECT_TRUE(done->done);
}

TEST_F(FrameSplitGLTest, TileCountIsClampedToTheImageHeight) {
  Job j = loadAsset("cornell_box/cornell_box.json", 16, 5, 2);
  auto r = makeRenderer(j);
  ASSERT_TRUE(r);
  r->setFrameTiles(1000);
  EXPECT_EQ(r->frameTiles(), kMaxFrameTiles);
  auto p = r->stepPart();
  ASSERT_TRUE(p.ok());
  // Frame 1 (first light: the box has no environment): the lamp's shadow map, then lighting +
  // accumulation, one band per row at most (the probe volume captures nothing before the
  // first image after a reset).
  EXPECT_EQ(p->parts, 6);
  while (!p->done) p = r->stepPart();
  // Unsplit, one part is the whole frame.
  r->setFrameTiles(0);
  EXPECT_EQ(r->frameTiles(), 1);
  p = r->stepPart();
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->frame, 2);
  EXPECT_TRUE(p->done);
  EXPECT_EQ(p->part, 1);
  EXPECT_EQ(p->parts, 1);
}

}  // namespace
}  // namespace penumbra::test
