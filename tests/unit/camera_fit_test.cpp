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

// A scene of one instanced mesh with these vertices (one triangle fan over them).
Scene sceneOf(const std::vector<glm::vec3>& vertices, const glm::mat4& world = glm::mat4(1.0f)) {
  Scene s;
  Mesh mesh;
  Primitive p;
  p.positions = vertices;
  for (uint32_t i = 1; i + 1 < vertices.size(); ++i)
    p.indices.insert(p.indices.end(), {0, i, i + 1});
  for (const glm::vec3& v : vertices) p.bounds.extend(v);
  mesh.primitives.push_back(p);
  s.meshes.push_back(mesh);
  Instance inst;
  inst.mesh = 0;
  inst.world = world;
  s.instances.push_back(inst);
  for (const glm::vec3& v : vertices) s.bounds.extend(glm::vec3(world * glm::vec4(v, 1.0f)));
  return s;
}

// The smallest rectangle holding every vertex in NDC: {min x, min y, max x, max y}.
glm::vec4 ndcExtent(const CameraMatrices& m, const Scene& s) {
  glm::vec4 e(1e9f, 1e9f, -1e9f, -1e9f);
  for (const Instance& inst : s.instances) {
    for (const Primitive& p : s.meshes[static_cast<size_t>(inst.mesh)].primitives) {
      for (const glm::vec3& v : p.positions) {
        const glm::vec2 q = ndc(m, glm::vec3(inst.world * glm::vec4(v, 1.0f)));
        e = glm::vec4(glm::min(glm::vec2(e), q), glm::max(glm::vec2(e.z, e.w), q));
      }
    }
  }
  return e;
}

// model-viewer fills its element with the model; the sphere around the bounds left a flat board
// or a long car small and an asymmetric model (FlightHelmet) off-centre. The fit: every vertex
// in view, the binding axis 92 % full, both axes centred, in landscape, square and portrait.
TEST(CameraFitTest, AutomaticFramingFillsTheViewCentred) {
  std::vector<glm::vec3> board;  // a flat 8 x 8 board with one tall piece in a corner
  for (float x : {-4.0f, 4.0f})
    for (float z : {-4.0f, 4.0f}) board.emplace_back(x, 0.0f, z);
  board.emplace_back(3.5f, 1.5f, 3.5f);
  std::vector<glm::vec3> car;  // long along X, low
  for (int c = 0; c < 8; ++c)
    car.emplace_back(c & 1 ? 2.2f : -2.2f, c & 2 ? 1.3f : 0.0f, c & 4 ? 0.9f : -0.9f);
  std::vector<glm::vec3> helmet;  // tall, its mass off the bounds' centre
  for (int c = 0; c < 8; ++c)
    helmet.emplace_back(c & 1 ? 0.2f : -0.2f, c & 2 ? 0.6f : 0.0f, c & 4 ? 0.2f : -0.2f);
  helmet.emplace_back(0.0f, 0.9f, 0.6f);
  const glm::mat4 turned = glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(0, 1, 0));
  const std::vector<std::pair<const char*, Scene>> scenes = {
      {"board", sceneOf(board)}, {"car", sceneOf(car)}, {"helmet", sceneOf(helmet, turned)}};
  for (const auto& [name, scene] : scenes) {
    for (const auto& [w, h] : {std::pair{1280, 720}, {500, 500}, {390, 844}}) {
      const Camera cam = defaultCamera(scene, static_cast<float>(w) / static_cast<float>(h));
      const glm::vec4 e = ndcExtent(cameraMatrices(cam, w, h, {0, 0}), scene);
      const std::string at = std::string(name) + " " + std::to_string(w) + "x" + std::to_string(h);
      EXPECT_GE(e.x, -0.921f) << at;
      EXPECT_GE(e.y, -0.921f) << at;
      EXPECT_LE(e.z, 0.921f) << at;
      EXPECT_LE(e.w, 0.921f) << at;
      EXPECT_GT(std::max(e.z - e.x, e.w - e.y), 2.0f * 0.9f) << at << ": the model is small";
      // Centred: in perspective the two sides' slack is equal in the fitting's terms, so the
      // NDC midpoints sit near 0 (a few per cent of the view for deep models).
      EXPECT_NEAR(0.5f * (e.x + e.z), 0.0f, 0.06f) << at;
      EXPECT_NEAR(0.5f * (e.y + e.w), 0.0f, 0.06f) << at;
      EXPECT_GT(cam.znear, 0.0f) << at;
    }
  }
}

}  // namespace
}  // namespace penumbra
