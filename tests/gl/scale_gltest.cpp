// Defaults that follow the scene's scale: the same scene modelled in centimetres, metres or
// hectometres renders the same image with default settings (the occlusion distance is derived
// from the scene's bounds, shadow biases and frusta from its radius). With a fixed occlusion
// distance the images differ, which is what the default avoids.
#include <gtest/gtest.h>

#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class ScaleGLTest : public GlFixture {};

struct Scaled {
  Scene scene;
  Camera camera;
};

// A floor, a box and a sphere touching both (contact occlusion), a rect light above.
Scaled sceneAtScale(float k) {
  Scene s;
  s.materials = {lambert(glm::vec3(0.7f)), lambert(glm::vec3(0.8f, 0.4f, 0.2f))};
  s.meshes.push_back(quadMesh(4.0f, 0.0f, 0));
  s.meshes.push_back(boxMesh({-1.0f, 0.0f, -0.8f}, {0.0f, 1.0f, 0.2f}, 1));
  s.meshes.push_back(sphereMesh({0.5f, 0.5f, 0.0f}, 0.5f, 0, 32));
  for (Mesh& m : s.meshes) {
    for (Primitive& p : m.primitives) {
      p.bounds = {};
      for (glm::vec3& v : p.positions) {
        v *= k;
        p.bounds.extend(v);
      }
    }
  }
  finishScene(s);
  Light light;
  light.position = glm::vec3(0.0f, 3.0f, 0.5f) * k;
  light.direction = {0, -1, 0};
  light.right = {1, 0, 0};
  light.up = {0, 0, 1};
  light.width = light.height = 1.0f * k;
  light.intensity = 2.0f;
  s.lights.push_back(light);
  Camera cam =
      lookAtCamera(glm::vec3(0.5f, 2.0f, 4.0f) * k, glm::vec3(0.0f, 0.4f, 0.0f) * k, 40.0f);
  cam.znear = 0.05f * k;
  return {std::move(s), cam};
}

Image renderAt(float k, float occlusionDistance) {
  const Scaled sc = sceneAtScale(k);
  RenderSettings rs;
  rs.width = rs.height = 64;
  rs.progressive.frames = 16;
  rs.progressive.shadowMapSize = 256;
  rs.progressive.occlusionDistance = occlusionDistance;
  auto img = renderRadiance(sc.scene, uniformEnvironment(glm::vec3(1.0f)), sc.camera, rs);
  EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.message());
  return img.ok() ? std::move(*img) : Image(64, 64, 4);
}

TEST_F(ScaleGLTest, DefaultSettingsGiveTheSameImageAtAnyScale) {
  const Image metres = renderAt(1.0f, 0.0f);
  for (float k : {0.01f, 100.0f}) {
    const Image scaled = renderAt(k, 0.0f);
    EXPECT_TRUE(matchesImage(scaled, metres, {.maxAbs = 0.05, .meanAbs = 0.002},
                             "scale_" + std::to_string(static_cast<int>(k * 100)) + "_percent"))
        << "scene scaled by " << k;
  }
}

TEST_F(ScaleGLTest, AFixedOcclusionDistanceDoesNotFollowTheScale) {
  // The control: 0.5 units is a different share of the scene at each scale.
  auto diff = compareImages(renderAt(0.01f, 0.5f), renderAt(1.0f, 0.5f));
  ASSERT_TRUE(diff.ok());
  EXPECT_GT(diff->meanAbs, 0.005) << "a fixed occlusion distance should change the image";
}

}  // namespace
}  // namespace penumbra::test
