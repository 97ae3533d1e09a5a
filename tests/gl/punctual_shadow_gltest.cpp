// Shadows of KHR_lights_punctual lights: a box on a floor lit from the side by a directional
// light, a spot light and a point light casts its shadow where the light's geometry puts it;
// the lit floor beside it stays lit. A point light's cube map shades every direction.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/constants.hpp>

#include "passes/camera_math.h"
#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class PunctualShadowGLTest : public GlFixture {};

constexpr int kPunctualSize = 96;

struct Render {
  Image image;
  CameraMatrices camera;
  // Radiance (mean of RGB) of the floor at world point p.
  float at(glm::vec3 p) const { return radianceAt(image, camera.projection * camera.view, p); }
};

Render renderWith(const Light& light, bool boxCastsShadow = true) {
  Scene s;
  s.materials = {lambert(glm::vec3(0.8f)), lambert(glm::vec3(0.5f))};
  s.meshes.push_back(quadMesh(5.0f, 0.0f, 0));
  s.meshes.push_back(boxMesh({-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}, 1));
  finishScene(s);
  s.instances[1].castsShadow = boxCastsShadow;
  s.lights.push_back(light);
  const Camera cam = lookAtCamera({0.0f, 7.0f, 0.01f}, {0.0f, 0.0f, 0.0f}, 40.0f);
  RenderSettings rs;
  rs.width = rs.height = kPunctualSize;
  rs.progressive.frames = 16;
  rs.progressive.directDelay = 0.0f;
  rs.progressive.shadowMapSize = 512;
  rs.progressive.screenSpaceIndirect = false;
  auto img = renderRadiance(s, uniformEnvironment(glm::vec3(0.0f)), cam, rs);
  EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.message());
  return {img.ok() ? std::move(*img) : Image(kPunctualSize, kPunctualSize, 4),
          cameraMatrices(cam, kPunctualSize, kPunctualSize, {0, 0})};
}

// Light travelling along +x and down at 45 degrees: the unit-high box's shadow covers the floor
// from x = 0.5 to 1.5 (|z| < 0.5).
void expectShadowBesideTheBox(const Render& r, const char* what) {
  (void)writeImage(outputDir() + "/punctual_" + what + ".png", r.image);  // to look at
  const float shadow = r.at({1.0f, 0.0f, 0.0f});
  const float litBefore = r.at({-1.2f, 0.0f, 0.0f});
  const float litBeside = r.at({1.0f, 0.0f, 1.3f});
  EXPECT_GT(litBefore, 0.05f) << what << ": the floor facing the light is lit";
  EXPECT_GT(litBeside, 0.05f) << what << ": the floor beside the shadow is lit";
  EXPECT_LT(shadow, 0.1f * litBeside) << what << ": the floor behind the box is in shadow";
}

TEST_F(PunctualShadowGLTest, DirectionalLightCastsAShadow) {
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
  sun.intensity = 2.0f;
  expectShadowBesideTheBox(renderWith(sun), "directional");
}

TEST_F(PunctualShadowGLTest, LampProxiesCastNoShadow) {
  // The same box as the visible face of a lamp (Instance::castsShadow false): the floor
  // behind it is as bright as beside it.
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
  sun.intensity = 2.0f;
  const Render r = renderWith(sun, false);
  EXPECT_NEAR(r.at({1.0f, 0.0f, 0.0f}), r.at({1.0f, 0.0f, 1.3f}), 0.05f * r.at({1.0f, 0.0f, 1.3f}));
}

TEST_F(PunctualShadowGLTest, SpotLightCastsAShadow) {
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {-2.0f, 2.5f, 0.0f};
  spot.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
  spot.outerConeAngle = glm::radians(60.0f);
  spot.innerConeAngle = glm::radians(50.0f);
  spot.intensity = 20.0f;
  // From (-2, 2.5) the box's top edge at x = 0.5, y = 1 shades the floor to x = 2.17.
  expectShadowBesideTheBox(renderWith(spot), "spot");
}

// The case reported black but for specks (issue #60): a spot pointing straight down (a node
// turned -90 degrees about X; its placement is scene_camera_light_test's) with a range beyond
// the floor lights a disc of the analytic irradiance, fades across the ring between the cone
// angles and leaves the floor outside dark.
TEST_F(PunctualShadowGLTest, SpotLightStraightDownLightsItsDisc) {
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {1.5f, 4.0f, 1.0f};
  spot.direction = {0.0f, -1.0f, 0.0f};
  spot.up = {0.0f, 0.0f, -1.0f};
  spot.innerConeAngle = 0.353f;
  spot.outerConeAngle = 0.393f;
  spot.intensity = 1000.0f;
  spot.range = 25.0f;
  const Render r = renderWith(spot);
  (void)writeImage(outputDir() + "/punctual_spot_down.png", r.image);  // to look at
  // E = I cos / d^2 with the glTF range window (1 - (d/range)^4)^2; L = albedo E / pi.
  auto expected = [&](glm::vec3 p) {
    const glm::vec3 v = spot.position - p;
    const float d = glm::length(v), window = 1.0f - std::pow(d / spot.range, 4.0f);
    return 0.8f * spot.intensity * (v.y / d) / (d * d) * window * window / glm::pi<float>();
  };
  const glm::vec3 centre(1.5f, 0.0f, 1.0f), inside(1.5f, 0.0f, 2.0f), ring(1.5f, 0.0f, -0.56f),
      outside(1.5f, 0.0f, -1.0f);
  EXPECT_NEAR(r.at(centre), expected(centre), 0.15f * expected(centre));
  EXPECT_NEAR(r.at(inside), expected(inside), 0.15f * expected(inside));
  EXPECT_GT(r.at(ring), 0.02f * expected(centre)) << "the ring between the cones is lit";
  EXPECT_LT(r.at(ring), 0.9f * expected(ring)) << "and fades";
  EXPECT_LT(r.at(outside), 0.01f * expected(centre)) << "outside the outer cone is dark";
}

TEST_F(PunctualShadowGLTest, PointLightCastsAShadow) {
  Light bulb;
  bulb.type = LightType::Point;
  bulb.position = {-2.0f, 2.5f, 0.0f};
  bulb.intensity = 20.0f;
  // As the spot light: the box's top edge shades the floor to x = 2.17.
  expectShadowBesideTheBox(renderWith(bulb), "point");
}

TEST_F(PunctualShadowGLTest, PointLightShadowsGoEveryWay) {
  // A bulb at (0, 2, 0) between three unit boxes (centred at x = +-1.5 and z = +1.5): each
  // shades the floor behind it (from 2 to 4 units out), through different cube faces, while
  // the floor at the same distance between the boxes stays lit.
  Scene s;
  s.materials = {lambert(glm::vec3(0.8f)), lambert(glm::vec3(0.5f))};
  s.meshes.push_back(quadMesh(10.0f, 0.0f, 0));
  s.meshes.push_back(boxMesh({1.0f, 0.0f, -0.5f}, {2.0f, 1.0f, 0.5f}, 1));
  s.meshes.push_back(boxMesh({-2.0f, 0.0f, -0.5f}, {-1.0f, 1.0f, 0.5f}, 1));
  s.meshes.push_back(boxMesh({-0.5f, 0.0f, 1.0f}, {0.5f, 1.0f, 2.0f}, 1));
  finishScene(s);
  Light bulb;
  bulb.type = LightType::Point;
  bulb.position = {0.0f, 2.0f, 0.0f};
  bulb.intensity = 20.0f;
  s.lights.push_back(bulb);
  const Camera cam = lookAtCamera({0.0f, 9.0f, 0.01f}, {0.0f, 0.0f, 0.0f}, 60.0f);
  RenderSettings rs;
  rs.width = rs.height = kPunctualSize;
  rs.progressive.frames = 8;
  rs.progressive.directDelay = 0.0f;
  rs.progressive.shadowMapSize = 512;
  rs.progressive.screenSpaceIndirect = false;
  auto img = renderRadiance(s, uniformEnvironment(glm::vec3(0.0f)), cam, rs);
  ASSERT_TRUE(img.ok()) << img.message();
  const Render r{std::move(*img), cameraMatrices(cam, kPunctualSize, kPunctualSize, {0, 0})};
  (void)writeImage(outputDir() + "/punctual_point_all_ways.png", r.image);  // to look at
  // Lit reference at the same distance from the bulb as the shadow points (3 units out).
  const float lit = r.at({2.12f, 0.0f, -2.12f});
  EXPECT_GT(lit, 0.05f);
  for (const glm::vec3 p : {glm::vec3(3, 0, 0), glm::vec3(-3, 0, 0), glm::vec3(0, 0, 3)}) {
    EXPECT_LT(r.at(p), 0.1f * lit) << "no shadow behind the box towards " << p.x << ", " << p.z;
  }
  EXPECT_GT(r.at({0.0f, 0.0f, -3.0f}), 0.8f * lit) << "the open side is lit";
}

}  // namespace
}  // namespace penumbra::test
