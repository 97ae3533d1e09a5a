// The progressive renderer end to end: white furnace, goldens, the sample schedule as seen
// in the passes it issues, convergence, determinism and the half-float path.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "penumbra/environment.h"
#include "penumbra/render_job.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class RendererGLTest : public GlFixture {};

struct Loaded {
  Scene scene;
  PackedEnvironment env;
  Camera camera;
  RenderSettings settings;
};

// A bundled scene file through the application layer, as every program loads it.
Loaded loadJob(const std::string& sceneFile,
               std::vector<std::pair<std::string, std::string>> overrides,
               EnvironmentLoadOptions panorama = {}) {
  JobRequest req;
  req.scenePath = sourceDir() + "/assets/" + sceneFile;
  req.settings = std::move(overrides);
  req.panorama = panorama;
  auto job = RenderJob::load(req);
  EXPECT_TRUE(job.ok()) << (job.ok() ? "" : job.message());
  if (!job) return {};
  return {std::move(job->scene), std::move(job->environment), job->camera, job->settings};
}

Loaded loadCornell(int size, int frames) {
  const std::string side = std::to_string(size);
  return loadJob("cornell_box/cornell_box.json", {{"width", side},
                                                  {"height", side},
                                                  {"frames", std::to_string(frames)},
                                                  {"shadowMapSize", "256"}});
}

std::unique_ptr<Renderer> makeRenderer(const Loaded& l, const RendererOptions& o = {}) {
  auto r = Renderer::create(o);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.message());
  EXPECT_TRUE((*r)->setSettings(l.settings).ok());
  EXPECT_TRUE((*r)->setScene(l.scene).ok());
  EXPECT_TRUE((*r)->setEnvironment(l.env).ok());
  (*r)->setCamera(l.camera);
  return std::move(*r);
}

void runToEnd(Renderer& r) {
  while (!r.converged()) ASSERT_TRUE(r.step().ok());
}

TEST_F(RendererGLTest, WhiteFurnaceLambertianSphereShowsTheEnvironment) {
  Scene s;
  s.materials.push_back(lambert(glm::vec3(1.0f)));
  s.meshes.push_back(sphereMesh({0, 0, 0}, 1.0f, 0, 96));
  finishScene(s);
  for (int frames : {1, 8}) {
    RenderSettings rs;
    rs.width = rs.height = 48;
    rs.progressive.frames = frames;
    auto img = renderRadiance(s, uniformEnvironment(glm::vec3(1.0f)),
                              lookAtCamera({0, 0, 4}, {0, 0, 0}, 20.0f), rs);
    ASSERT_TRUE(img.ok()) << img.message();
    int checked = 0;
    for (int y = 10; y < 38; ++y) {
      for (int x = 10; x < 38; ++x) {
        const float* p = img->pixel(x, y);
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(p[c], 1.0f, 0.01f)
              << "pixel " << x << "," << y << ", " << frames << " frames";
        }
        ++checked;
      }
    }
    EXPECT_GT(checked, 700);
  }
}

// An orthographic camera (ymag 2 on a 64-pixel-high image: 16 pixels per unit) sees a unit
// sphere as a disk of radius 16 pixels at the image centre, whatever its distance.
TEST_F(RendererGLTest, OrthographicCameraShowsASphereAtItsTrueSize) {
  Scene s;
  s.materials.push_back(lambert(glm::vec3(0.25f)));
  s.meshes.push_back(sphereMesh({0, 0, 0}, 1.0f, 0, 96));
  finishScene(s);
  for (float distance : {3.0f, 8.0f}) {
    Camera cam = lookAtCamera({0, 0, distance}, {0, 0, 0}, 20.0f);
    cam.orthographic = true;
    cam.ymag = 2.0f;
    cam.znear = 0.1f;
    cam.zfar = 20.0f;
    RenderSettings rs;
    rs.width = rs.height = 64;
    rs.progressive.frames = 16;
    auto img = renderRadiance(s, uniformEnvironment(glm::vec3(1.0f)), cam, rs);
    ASSERT_TRUE(img.ok()) << img.message();
    // Coverage per pixel from its radiance: background 1, sphere (a white furnace) uniform.
    const float inside = img->pixel(32, 32)[1];
    ASSERT_LT(inside, 0.5f);
    double area = 0.0, cx = 0.0, cy = 0.0;
    for (int y = 0; y < 64; ++y) {
      for (int x = 0; x < 64; ++x) {
        const double c = std::clamp((1.0 - img->pixel(x, y)[1]) / (1.0 - inside), 0.0, 1.0);
        area += c;
        cx += c * (x + 0.5);
        cy += c * (y + 0.5);
      }
    }
    EXPECT_NEAR(area, M_PI * 16.0 * 16.0, 0.02 * M_PI * 256.0) << "distance " << distance;
    EXPECT_NEAR(cx / area, 32.0, 0.25) << "distance " << distance;
    EXPECT_NEAR(cy / area, 32.0, 0.25) << "distance " << distance;
  }
}

// The Cornell box ceiling sees no direct light (the lamp faces down): all of it comes from
// screen-space indirect samples, so clamping their radiance darkens it, and the clamp's
// default (10) leaves this scene, whose bounce light is far below it, unchanged.
TEST_F(RendererGLTest, IndirectClampLimitsScreenSpaceBounceLight) {
  auto ceiling = [](float clamp) {
    Loaded l = loadCornell(64, 24);
    l.settings.progressive.indirectClamp = clamp;
    l.settings.progressive.probeVolume = false;  // the screen-space bounce alone
    auto r = makeRenderer(l);
    runToEnd(*r);
    auto img = r->readRadiance();
    EXPECT_TRUE(img.ok());
    double sum = 0.0;
    int n = 0;
    for (int y = 2; y < 8; ++y) {  // a band of ceiling beside the lamp
      for (int x = 8; x < 20; ++x, ++n) sum += img->pixel(x, y)[0];
    }
    return sum / n;
  };
  const double unclamped = ceiling(0.0f), byDefault = ceiling(10.0f), tight = ceiling(0.002f);
  EXPECT_GT(unclamped, 0.01);
  EXPECT_NEAR(byDefault, unclamped, 1e-6);
  EXPECT_LT(tight, 0.25 * unclamped);
}

TEST_F(RendererGLTest, CornellBoxConvergedMatchesGolden) {
  Loaded l = loadCornell(96, 128);
  auto r = makeRenderer(l);
  runToEnd(*r);
  auto img = r->readDisplay();
  ASSERT_TRUE(img.ok());
  EXPECT_TRUE(matchesGolden(*img, sourceDir() + "/tests/golden/cornell_box_m128.png",
                            {.maxAbs = 0.08, .meanAbs = 0.004}, "cornell_box_m128"));
}

TEST_F(RendererGLTest, MaterialGridMatchesGolden) {
  Loaded l = loadJob("material_grid/material_grid.json",
                     {{"width", "128"}, {"height", "96"}, {"frames", "16"}},
                     {.faceSize = 32, .samples = 32});
  auto r = makeRenderer(l);
  runToEnd(*r);
  auto img = r->readDisplay();
  ASSERT_TRUE(img.ok());
  EXPECT_TRUE(matchesGolden(*img, sourceDir() + "/tests/golden/material_grid_m16.png",
                            {.maxAbs = 0.08, .meanAbs = 0.004}, "material_grid_m16"));
}

TEST_F(RendererGLTest, ShowroomMatchesGolden) {
  // Clearcoat, sheen, a solid glass ball (refraction, Beer-Lambert) and a tinted thin-walled
  // pane against high-contrast silhouettes.
  Loaded l =
      loadJob("showroom/showroom.json", {{"width", "120"}, {"height", "80"}, {"frames", "32"}},
              {.faceSize = 32, .samples = 32});
  auto r = makeRenderer(l);
  runToEnd(*r);
  auto img = r->readDisplay();
  ASSERT_TRUE(img.ok());
  EXPECT_TRUE(matchesGolden(*img, sourceDir() + "/tests/golden/showroom_m32.png",
                            {.maxAbs = 0.1, .meanAbs = 0.004}, "showroom_m32"));
}

TEST_F(RendererGLTest, FrameOneIsEnvironmentOnlyAndShadowPassesFollowThePlan) {
  Loaded l = loadCornell(32, 32);
  // An environment that carries the scene (no first light): the f_d delay applies.
  l.env = uniformEnvironment(glm::vec3(20.0f));
  {
    // Sky shadows: one shadow map a frame from frame 2 (occlusion on), none in frame 1.
    Loaded withSky = l;
    withSky.settings.progressive.skyShadows = true;
    auto sky = makeRenderer(withSky);
    ASSERT_EQ(*sky->step(), 1);
    EXPECT_EQ(sky->lastFrame().shadowPasses, 0);
    ASSERT_EQ(*sky->step(), 2);
    EXPECT_EQ(sky->lastFrame().shadowPasses, 1);
  }
  l.settings.progressive.skyShadows = false;  // the rest counts area-light samples
  auto r = makeRenderer(l);
  ASSERT_EQ(*r->step(), 1);
  EXPECT_EQ(r->lastFrame().shadowPasses, 0);
  EXPECT_FALSE(r->lastFrame().prepass);
  EXPECT_FALSE(r->lastFrame().occlusion);
  ASSERT_EQ(*r->step(), 2);
  EXPECT_TRUE(r->lastFrame().prepass);
  EXPECT_TRUE(r->lastFrame().occlusion);
  int total = 0, minPerFrame = 1 << 20, maxPerFrame = 0;
  while (!r->converged()) {
    ASSERT_TRUE(r->step().ok());
    const int frame = r->lastFrame().frame;
    const int n = r->lastFrame().shadowPasses;
    total += n;
    EXPECT_FALSE(r->lastFrame().prepass) << "the prepass is rendered once per camera";
    if (frame >= static_cast<int>(32 * 0.3f)) {
      minPerFrame = std::min(minPerFrame, n);
      maxPerFrame = std::max(maxPerFrame, n);
    } else {
      EXPECT_EQ(n, 0) << "no direct light before frame floor(m f_d), frame " << frame;
    }
  }
  EXPECT_GT(total, 0);
  EXPECT_LE(maxPerFrame - minPerFrame, 1);
  // Restarting (a camera change) begins again at frame 1 with no shadow pass.
  r->setCamera(l.camera);
  ASSERT_EQ(*r->step(), 1);
  EXPECT_EQ(r->lastFrame().shadowPasses, 0);
}

TEST_F(RendererGLTest, DarkEnvironmentLightsFrameOneAndStartsDirectLightAtFrameTwo) {
  Loaded l = loadCornell(24, 32);             // black environment
  l.settings.progressive.skyShadows = false;  // counted above; here: area-light samples only
  auto r = makeRenderer(l);
  ASSERT_EQ(*r->step(), 1);
  EXPECT_EQ(r->lastFrame().shadowPasses, 1) << "first light: the lamp from its centre";
  ASSERT_EQ(*r->step(), 2);
  EXPECT_GT(r->lastFrame().shadowPasses, 0);
  // Turning the environment up (it then carries the scene) restores the delay.
  RenderSettings s = l.settings;
  s.environmentIntensity = 1.0f;
  ASSERT_TRUE(r->setEnvironment(uniformEnvironment(glm::vec3(20.0f))).ok());
  ASSERT_TRUE(r->setSettings(s).ok());
  ASSERT_EQ(*r->step(), 1);
  ASSERT_EQ(*r->step(), 2);
  EXPECT_EQ(r->lastFrame().shadowPasses, 0);
}

TEST_F(RendererGLTest, ErrorAgainstLongRunFallsWithFrames) {
  Loaded l = loadCornell(40, 1024);
  auto r = makeRenderer(l);
  std::vector<std::pair<int, Image>> snapshots;
  // Same schedule shape for every m: compare frame k of a 128-frame run with 1024 frames.
  l.settings.progressive.frames = 128;
  auto r128 = makeRenderer(l);
  int next = 1;
  while (!r128->converged()) {
    auto f = r128->step();
    ASSERT_TRUE(f.ok());
    if (*f == next) {
      snapshots.emplace_back(*f, *r128->readRadiance());
      next *= 2;
    }
  }
  runToEnd(*r);
  auto reference = r->readRadiance();
  ASSERT_TRUE(reference.ok());
  std::vector<double> errors;
  for (auto& [frame, img] : snapshots) errors.push_back(rmse(img, *reference));
  ASSERT_EQ(errors.size(), 8u);
  for (size_t i = 1; i < errors.size(); ++i) {
    EXPECT_LE(errors[i], errors[i - 1] * 1.15) << "frame " << snapshots[i].first;
  }
  EXPECT_LT(errors.back(), 0.35 * errors.front());
}

TEST_F(RendererGLTest, SameInputsAndSeedGiveBitIdenticalImages) {
  Loaded l = loadCornell(32, 24);
  auto a = makeRenderer(l);
  auto b = makeRenderer(l);
  runToEnd(*a);
  runToEnd(*b);
  auto ia = a->readRadiance(), ib = b->readRadiance();
  ASSERT_TRUE(ia.ok() && ib.ok());
  EXPECT_EQ(ia->pixels, ib->pixels);
  l.settings.progressive.seed = 99;
  auto c = makeRenderer(l);
  runToEnd(*c);
  EXPECT_NE(c->readRadiance()->pixels, ia->pixels) << "the seed must change the samples";
}

// `image` resized to width x height by bilinear interpolation between pixel centres (clamped
// at the borders), as a reference for the preview's upsampling.
Image bilinearResize(const Image& image, int width, int height) {
  Image out(width, height, image.channels);
  const auto at = [&](int x, int y, int c) {
    x = std::clamp(x, 0, image.width - 1);
    y = std::clamp(y, 0, image.height - 1);
    return image.pixel(x, y)[c];
  };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float px = (x + 0.5f) * image.width / width - 0.5f;
      const float py = (y + 0.5f) * image.height / height - 0.5f;
      const int x0 = static_cast<int>(std::floor(px)), y0 = static_cast<int>(std::floor(py));
      const float fx = px - x0, fy = py - y0;
      for (int c = 0; c < image.channels; ++c) {
        const float bottom = at(x0, y0, c) + (at(x0 + 1, y0, c) - at(x0, y0, c)) * fx;
        const float top = at(x0, y0 + 1, c) + (at(x0 + 1, y0 + 1, c) - at(x0, y0 + 1, c)) * fx;
        out.pixel(x, y)[c] = bottom + (top - bottom) * fy;
      }
    }
  }
  return out;
}

TEST_F(RendererGLTest, PreviewIsFrameOneAtAQuarterOfThePixelsAndStaysOutOfTheMean) {
  Loaded l = loadJob("material_grid/material_grid.json",
                     {{"width", "96"}, {"height", "72"}, {"frames", "8"}},
                     {.faceSize = 32, .samples = 32});
  // Without the probe volume, whose captures (kept across views) would change frame 1.
  l.settings.progressive.probeVolume = false;
  auto fresh = makeRenderer(l);
  ASSERT_EQ(*fresh->step(), 1);
  auto frame1 = fresh->readRadiance();
  ASSERT_TRUE(frame1.ok());
  Loaded half = l;
  half.settings.width = 48;
  half.settings.height = 36;
  auto small = makeRenderer(half);
  ASSERT_EQ(*small->step(), 1);
  auto smallFrame1 = small->readRadiance();
  ASSERT_TRUE(smallFrame1.ok());

  // A preview in the middle of a run (the view started to move): frame 1 at 48x36, upsampled.
  auto r = makeRenderer(l);
  ASSERT_TRUE(r->step().ok());
  ASSERT_TRUE(r->step().ok());
  ASSERT_TRUE(r->preview().ok());
  EXPECT_EQ(r->framesDone(), 0);
  auto preview = r->readRadiance();
  ASSERT_TRUE(preview.ok());
  const Image expected = bilinearResize(*smallFrame1, 96, 72);
  const double err = rmse(*preview, expected);
  std::printf("preview: rmse %.6f against frame 1 at 48x36 upsampled, %.6f against frame 1\n", err,
              rmse(*preview, *frame1));
  EXPECT_LT(err, 1e-4);
  EXPECT_GT(rmse(*preview, *frame1), 100 * err) << "a quarter of the pixels, not frame 1";
  // It stays out of the mean: the next step draws frame 1 as a fresh renderer does.
  ASSERT_EQ(*r->step(), 1);
  EXPECT_EQ(r->readRadiance()->pixels, frame1->pixels);

  // At scale 1 the preview is frame 1 itself.
  l.settings.progressive.previewScale = 1.0f;
  auto whole = makeRenderer(l);
  ASSERT_TRUE(whole->preview().ok());
  EXPECT_LT(rmse(*whole->readRadiance(), *frame1), 1e-5);
}

TEST_F(RendererGLTest, HalfFloatAccumulationConvergesToTheFloatResult) {
  Loaded l = loadCornell(32, 64);
  auto full = makeRenderer(l);
  auto half = makeRenderer(l, {.forceHalfFloat = true});
  runToEnd(*full);
  runToEnd(*half);
  auto a = full->readRadiance(), b = half->readRadiance();
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_LT(rmse(*a, *b), 0.01);
}

TEST_F(RendererGLTest, NonFiniteSamplesDoNotPoisonTheImage) {
  Loaded l = loadCornell(24, 16);
  l.scene.lights.at(0).intensity = std::nanf("");
  auto r = makeRenderer(l);
  runToEnd(*r);
  auto img = r->readRadiance();
  ASSERT_TRUE(img.ok());
  for (float v : img->pixels) ASSERT_TRUE(std::isfinite(v));
}

}  // namespace
}  // namespace penumbra::test

namespace penumbra::test {
namespace {

// Three stacked squares seen from above: each pixel must show the nearest one (the lighting
// pass shades after a depth-only pass of the same geometry, with LEQUAL: a position that came
// out differently in the two programs would leave holes or show a lower square), and the draw
// order must not change a single value.
TEST_F(RendererGLTest, OverlappingSurfacesShowTheNearestWhateverTheDrawOrder) {
  auto render = [](bool reversed) {
    Scene s;
    const float albedo[3] = {0.8f, 0.5f, 0.2f};
    for (int i = 0; i < 3; ++i) {
      const int k = reversed ? 2 - i : i;
      s.materials.push_back(lambert(glm::vec3(albedo[k])));
      s.meshes.push_back(quadMesh(4.0f - static_cast<float>(k), 0.1f * static_cast<float>(k), i));
    }
    finishScene(s);
    RenderSettings rs;
    rs.width = rs.height = 40;
    rs.progressive.frames = 4;
    return renderRadiance(s, uniformEnvironment(glm::vec3(1.0f)),
                          lookAtCamera({0, 6, 0.01f}, {0, 0, 0}, 30.0f), rs);
  };
  auto a = render(false);
  auto b = render(true);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->pixels, b->pixels);
  // The top square (side 2, albedo 0.2, open sky above) covers the central pixels: under a
  // uniform sky of 1 they all show about the same radiance, its albedo plus its (F0 0.04)
  // specular reflection, well below the squares under it (0.5 and 0.8). (The probe volume's
  // layer above the stack, still filling after 4 frames, varies it by about 0.1 %.)
  const float centre = a->pixel(20, 20)[1];
  EXPECT_GT(centre, 0.2f);
  EXPECT_LT(centre, 0.25f);
  for (int y = 14; y < 26; ++y) {
    for (int x = 14; x < 26; ++x) EXPECT_NEAR(a->pixel(x, y)[1], centre, 1e-3f) << x << "," << y;
  }
}

// Frame targets and shadow maps are made by the first frame, at the settings then in force: a
// viewer sets its canvas's size, then a scene's settings, before it draws, and each size set
// on the way must not be allocated (a browser zero-fills every allocation).
TEST_F(RendererGLTest, SettingsBeforeTheFirstFrameAllocateOnlyTheLastSize) {
  Loaded l = loadCornell(32, 4);
  ASSERT_FALSE(l.scene.meshes.empty());
  const int64_t before = Renderer::gpuMemoryBytes();
  auto r = Renderer::create();
  ASSERT_TRUE(r.ok()) << r.message();
  Renderer& renderer = **r;
  // 1024x1024 with 2048 shadow maps: more than 100 MB of targets if they were made now.
  RenderSettings big = l.settings;
  big.width = big.height = 1024;
  big.progressive.shadowMapSize = 2048;
  ASSERT_TRUE(renderer.setSettings(big).ok());
  ASSERT_TRUE(renderer.setScene(l.scene).ok());
  ASSERT_TRUE(renderer.setEnvironment(l.env).ok());
  renderer.setCamera(l.camera);
  const int64_t created = Renderer::gpuMemoryBytes() - before;
  // The scene, the environment, lookup tables and the probe atlas, not the 1024x1024 targets
  // (16 MB a float target).
  EXPECT_LT(created, int64_t{16} << 20) << created;
  ASSERT_TRUE(renderer.setSettings(l.settings).ok());  // 32x32, 256 shadow maps
  EXPECT_EQ(Renderer::gpuMemoryBytes() - before, created);
  ASSERT_TRUE(renderer.step().ok());
  const int64_t drawn = Renderer::gpuMemoryBytes() - before;
  // The 32x32 targets and 256-pixel shadow maps (under 8 MB with the probe volume's maps).
  EXPECT_GT(drawn, created);
  EXPECT_LT(drawn, created + (int64_t{8} << 20)) << drawn - created;
  // A resize drops the targets at once and makes the new ones when the next frame draws.
  RenderSettings wide = l.settings;
  wide.width = 64;
  ASSERT_TRUE(renderer.setSettings(wide).ok());
  EXPECT_LT(Renderer::gpuMemoryBytes() - before, drawn);
  ASSERT_TRUE(renderer.step().ok());
  EXPECT_GT(Renderer::gpuMemoryBytes() - before, drawn);
  r->reset();
  EXPECT_EQ(Renderer::gpuMemoryBytes(), before);
}

}  // namespace
}  // namespace penumbra::test
