// Camera fit: a viewport wider than the camera's aspect keeps the vertical extent, a narrower
// (portrait) one keeps the horizontal extent, so a phone in portrait still shows the whole
// frame. For perspective and orthographic cameras and the automatic framing.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "passes/camera_math.h"
#include "penumbra/scene.h"

namespace penumbra {
namespace {

// Normalised device x and y of a world point.
glm::vec2 ndc(const CameraMatrices& m, glm::vec3 p) {
  const glm::vec4 c = m.projection * m.view * glm::vec4(p, 1.0f);
  return glm::vec2(c) / c.w;
}

Camera lookingDownZ(bool ortho) {
  Camera c;
  c.world = glm::mat4(1.0f);  // at the origin, looking down -Z
  c.yfov = 0.8f;
  c.aspect = 1.0f;
  c.znear = 0.1f;
  c.zfar = 100.0f;
  c.orthographic = ortho;
  c.ymag = 2.0f;
  return c;
}

TEST(CameraFitTest, PortraitKeepsTheHorizontalExtentLandscapeTheVertical) {
  for (bool ortho : {false, true}) {
    const Camera cam = lookingDownZ(ortho);
    const float half = ortho ? cam.ymag : std::tan(0.5f * cam.yfov) * 10.0f;
    const glm::vec3 rightEdge(half, 0.0f, -10.0f), topEdge(0.0f, half, -10.0f);
    const CameraMatrices square = cameraMatrices(cam, 100, 100, {0, 0});
    EXPECT_NEAR(ndc(square, rightEdge).x, 1.0f, 1e-4f) << "ortho " << ortho;
    EXPECT_NEAR(ndc(square, topEdge).y, 1.0f, 1e-4f) << "ortho " << ortho;
    // Portrait (1:2): the right edge stays at the border, the top edge moves inward.
    const CameraMatrices portrait = cameraMatrices(cam, 50, 100, {0, 0});
    EXPECT_NEAR(ndc(portrait, rightEdge).x, 1.0f, 1e-4f) << "ortho " << ortho;
    EXPECT_NEAR(ndc(portrait, topEdge).y, 0.5f, 1e-4f) << "ortho " << ortho;
    // Landscape (2:1): the top edge stays, the sides show more.
    const CameraMatrices landscape = cameraMatrices(cam, 200, 100, {0, 0});
    EXPECT_NEAR(ndc(landscape, topEdge).y, 1.0f, 1e-4f) << "ortho " << ortho;
    EXPECT_NEAR(ndc(landscape, rightEdge).x, 0.5f, 1e-4f) << "ortho " << ortho;
  }
}

TEST(CameraFitTest, WithoutAnAspectTheViewportDecides) {
  Camera cam = lookingDownZ(false);
  cam.aspect = 0.0f;  // a glTF camera without aspectRatio
  const glm::vec3 topEdge(0.0f, std::tan(0.5f * cam.yfov) * 10.0f, -10.0f);
  EXPECT_NEAR(ndc(cameraMatrices(cam, 50, 100, {0, 0}), topEdge).y, 1.0f, 1e-4f);
}

TEST(CameraFitTest, AutomaticFramingShowsTheWholeSceneInPortrait) {
  Scene s;
  s.bounds.extend(glm::vec3(-2.0f, 0.0f, -1.0f));
  s.bounds.extend(glm::vec3(2.0f, 1.0f, 1.0f));
  const Camera cam = defaultCamera(s);
  const CameraMatrices portrait = cameraMatrices(cam, 390, 844, {0, 0});
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 corner((c & 1) ? s.bounds.max.x : s.bounds.min.x,
                           (c & 2) ? s.bounds.max.y : s.bounds.min.y,
                           (c & 4) ? s.bounds.max.z : s.bounds.min.z);
    const glm::vec2 p = ndc(portrait, corner);
    EXPECT_LE(std::abs(p.x), 1.0f) << "corner " << c << " is off screen";
    EXPECT_LE(std::abs(p.y), 1.0f) << "corner " << c << " is off screen";
  }
}

}  // namespace
}  // namespace penumbra
