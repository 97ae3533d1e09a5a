// Diffuse occlusion rays at a quarter of the pixels (RendererOptions::quarterOcclusion,
// passes/occlusion_pass.h): each 2x2 block traces one ray a frame and its pixels share it. The
// converged image must stay the one a ray per pixel gives, contacts included, and both must
// differ from an image without occlusion (so the comparison can fail). And a floor lit only by
// a glowing wall beside it against the form factor: screen-space rays and the probe volume
// together must bring the wall's light once, not once and a half.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "passes/camera_math.h"
#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class OcclusionGLTest : public GlFixture {};

// A floor, a box and a sphere touching both, under a uniform sky: the contacts darken only by
// occlusion (no lights, no probe volume), the light they lose partly returned by screen-space
// indirect light.
Image render(bool quarter, float occlusionDistance) {
  Scene s;
  s.materials = {lambert(glm::vec3(0.7f)), lambert(glm::vec3(0.8f, 0.4f, 0.2f))};
  s.meshes.push_back(quadMesh(4.0f, 0.0f, 0));
  s.meshes.push_back(boxMesh({-1.0f, 0.0f, -0.8f}, {0.0f, 1.0f, 0.2f}, 1));
  s.meshes.push_back(sphereMesh({0.5f, 0.5f, 0.0f}, 0.5f, 0, 32));
  finishScene(s);
  Camera cam = lookAtCamera({0.5f, 2.0f, 4.0f}, {0.0f, 0.4f, 0.0f}, 40.0f);
  RenderSettings rs;
  rs.width = 96;
  rs.height = 96;
  rs.progressive.frames = 64;
  rs.progressive.probeVolume = false;
  rs.progressive.occlusionDistance = occlusionDistance;
  auto img = renderRadiance(s, uniformEnvironment(glm::vec3(1.0f)), cam, rs,
                            {.quarterOcclusion = quarter});
  EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.message());
  return img.ok() ? std::move(*img) : Image(96, 96, 4);
}

// The mean over each k x k tile: what is left of a difference once the noise is averaged out.
Image boxDown(const Image& image, int k) {
  Image out(image.width / k, image.height / k, image.channels);
  for (int y = 0; y < out.height * k; ++y) {
    for (int x = 0; x < out.width * k; ++x) {
      for (int c = 0; c < image.channels; ++c) {
        out.pixel(x / k, y / k)[c] += image.pixel(x, y)[c] / static_cast<float>(k * k);
      }
    }
  }
  return out;
}

TEST_F(OcclusionGLTest, QuarterResolutionRaysKeepTheImage) {
  const Image quarter = render(true, 0.0f), full = render(false, 0.0f);
  // Rays too short to reach anything: no occlusion at all.
  const Image open = render(true, 1e-5f);
  auto same = compareImages(quarter, full);
  auto without = compareImages(full, open);
  // Over 4x4 tiles, where 64 frames' noise has mostly averaged out: the bias.
  auto bias = compareImages(boxDown(quarter, 4), boxDown(full, 4));
  auto effect = compareImages(boxDown(full, 4), boxDown(open, 4));
  ASSERT_TRUE(same.ok() && without.ok() && bias.ok() && effect.ok());
  std::printf(
      "quarter against full: max %.4f mean %.5f, over 4x4 tiles mean %.5f; full "
      "against no occlusion: max %.4f mean %.5f, over tiles %.5f\n",
      same->maxAbs, same->meanAbs, bias->meanAbs, without->maxAbs, without->meanAbs,
      effect->meanAbs);
  // Measured: occlusion changes the image by 0.024 on average, the quarter-resolution rays
  // differ from a ray per pixel by 0.0044 (0.0027 between two seeds of a ray per pixel: the
  // rest is noise of rays shared by a block) and by 0.0018 over tiles.
  EXPECT_GT(without->meanAbs, 0.02) << "the scene must show occlusion";
  EXPECT_LT(bias->meanAbs, 0.15 * effect->meanAbs);
  EXPECT_TRUE(matchesImage(quarter, full, {.maxAbs = 0.2, .meanAbs = 0.006}, "occlusion_quarter"));
}

// Form factor from a floor point (x, 0, z), z > 0, normal +y, to the wall x in [-1, 1],
// y in [0, 1], z = 0, normal +z: the corner's closed form, Lambert's contour formula for a
// polygon, F = 1/(2 pi) |sum_i angle(R_i, R_i+1) n . unit(R_i x R_i+1)| over the unit vectors R_i
// from the point to the corners (agrees with a 400 x 200 midpoint rule to 1e-4 at the points
// used; the wall's bottom edge lies in the floor's plane, which the formula handles exactly).
double wallFormFactor(double x, double z) {
  const glm::dvec3 p{x, 0.0, z}, n{0.0, 1.0, 0.0};
  const std::array<glm::dvec3, 4> corners{
      {{-1.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, {-1.0, 1.0, 0.0}}};
  double sum = 0.0;
  for (size_t i = 0; i < corners.size(); ++i) {
    const glm::dvec3 a = glm::normalize(corners[i] - p);
    const glm::dvec3 b = glm::normalize(corners[(i + 1) % corners.size()] - p);
    const glm::dvec3 c = glm::cross(a, b);
    sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, c) / glm::length(c);
  }
  return std::abs(sum) / (2.0 * std::numbers::pi);
}

// Light that reaches the floor only from the wall's emission (no lights, black environment,
// a black wall so nothing comes back): where the occlusion rays hit the wall they bring its
// radiance, where they miss the probe volume answers. A miss used to take the probes' whole
// irradiance, the wall's share included, so the floor near the wall got the wall's light once
// and a half (1.33 x the form factor); the rays now correct only their own direction's share
// (0.96 x).
TEST_F(OcclusionGLTest, FloorBesideAGlowingWallGetsItsLightOnce) {
  const float rho = 0.5f;
  Material floor = lambert(glm::vec3(rho));
  floor.specularFactor = 0.0f;  // pure Lambert: radiance = albedo x irradiance / pi
  Material wall = lambert(glm::vec3(0.0f));
  wall.specularFactor = 0.0f;
  wall.emissiveFactor = glm::vec3(1.0f);
  Scene s;
  s.materials = {floor, wall};
  s.meshes.push_back(rectangle({-1.5f, 0, 0}, {3, 0, 0}, {0, 0, 2.5f}, {0, 1, 0}, 0));
  s.meshes.push_back(rectangle({-1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 1}, 1));
  finishScene(s);
  const Camera cam = lookAtCamera({0.0f, 1.6f, 2.8f}, {0.0f, 0.3f, 0.3f}, 60.0f);
  RenderSettings rs;
  rs.width = rs.height = 96;
  rs.progressive.frames = 128;
  rs.showBackground = false;
  // Probes close enough together to see the floor's gradient (the default grid has one layer,
  // at half the wall's height, whose upward hemisphere sees only the wall's upper half: alone
  // it gives half the light here), captured quickly: what is measured is how the rays and the
  // probes combine, not how coarse the grid is.
  rs.progressive.probeDensity = 8.0f;
  rs.progressive.probesPerFrame = 16;
  auto img = renderRadiance(s, uniformEnvironment(glm::vec3(0.0f)), cam, rs);
  ASSERT_TRUE(img.ok()) << img.message();
  const CameraMatrices cm = cameraMatrices(cam, rs.width, rs.height, {0, 0});
  double measured = 0.0, expected = 0.0;
  for (float z : {0.15f, 0.3f, 0.5f, 0.8f}) {
    for (float x : {-0.4f, 0.0f, 0.4f}) {
      const double e = rho * wallFormFactor(x, z);
      const double m = radianceAt(*img, cm.projection * cm.view, {x, 0.0f, z}, true);
      std::printf("# floor at (%.2f, %.2f): %.4f, form factor gives %.4f\n", x, z, m, e);
      measured += m;
      expected += e;
    }
  }
  std::printf("floor beside the wall: %.4f of the form factor's light\n", measured / expected);
  // The rest is the probes' interpolation, which answers for the rays that miss (the march's
  // four steps overshoot the wall's top edge).
  EXPECT_NEAR(measured / expected, 1.0, 0.1);
}

// A scene whose surfaces face no other (one convex body, one plane) skips the occlusion rays
// and the probe volume, which could only find the sky; a body on a floor keeps both.
TEST_F(OcclusionGLTest, ScenesThatCannotSeeThemselvesSkipTheRaysAndTheVolume) {
  const auto run = [](bool withFloor, ProbeVolumeInfo* info, int* occludedFrames) {
    Scene s;
    s.materials = {lambert(glm::vec3(0.7f))};
    s.meshes.push_back(sphereMesh({0.0f, 1.0f, 0.0f}, 0.6f, 0, 32));
    if (withFloor) s.meshes.push_back(quadMesh(6.0f, 0.0f, 0));
    finishScene(s);
    RenderSettings rs;
    rs.width = rs.height = 48;
    rs.progressive.frames = 32;
    auto r = Renderer::create();
    EXPECT_TRUE(r.ok());
    EXPECT_TRUE((*r)->setSettings(rs).ok());
    EXPECT_TRUE((*r)->setScene(s).ok());
    EXPECT_TRUE((*r)->setEnvironment(uniformEnvironment(glm::vec3(1.0f))).ok());
    (*r)->setCamera(lookAtCamera({0.0f, 1.0f, 3.0f}, {0.0f, 1.0f, 0.0f}, 30.0f));
    *occludedFrames = 0;
    while (!(*r)->converged()) {
      EXPECT_TRUE((*r)->step().ok());
      if ((*r)->lastFrame().occlusion) ++*occludedFrames;
    }
    *info = (*r)->probeVolumeInfo();
    auto img = (*r)->readRadiance();
    EXPECT_TRUE(img.ok());
    return img.ok() ? std::move(*img) : Image(48, 48, 4);
  };
  ProbeVolumeInfo alone, onFloor;
  int occludedAlone = -1, occludedOnFloor = -1;
  const Image sphere = run(false, &alone, &occludedAlone);
  run(true, &onFloor, &occludedOnFloor);
  EXPECT_EQ(alone.probes, 0);
  EXPECT_EQ(occludedAlone, 0);
  EXPECT_GT(onFloor.probes, 0);
  EXPECT_GT(occludedOnFloor, 8);
  // The lone sphere under a uniform sky of 1 shows its albedo's radiance where it faces the
  // camera (a white furnace: nothing may be lost to occlusion or leak from the probes).
  EXPECT_NEAR(sphere.pixel(24, 24)[1], 0.7f, 0.03f);
}

}  // namespace
}  // namespace penumbra::test
