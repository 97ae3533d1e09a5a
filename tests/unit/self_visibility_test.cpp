// surfacesSeeEachOther: which scenes the probe volume and the occlusion rays can skip.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/self_visibility.h"

namespace penumbra {
namespace {

// A unit cube at the origin, its triangles counter-clockwise seen from outside (glTF's front).
Primitive cube() {
  Primitive p;
  for (int i = 0; i < 8; ++i) {
    p.positions.emplace_back(i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f);
  }
  // Faces as quads a, b, c, d counter-clockwise from outside.
  const int quads[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3},
                           {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
  for (const auto& q : quads) {
    for (int k : {q[0], q[1], q[2], q[0], q[2], q[3]})
      p.indices.push_back(static_cast<uint32_t>(k));
  }
  return p;
}

// A 2x2 square in the y = 0 plane facing +y.
Primitive square() {
  Primitive p;
  p.positions = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
  p.indices = {0, 2, 1, 0, 3, 2};
  return p;
}

// A UV sphere as test scenes build it: its poles' triangles are slivers in floating point.
Primitive uvSphere(int segments) {
  Primitive p;
  const int rings = segments / 2;
  for (int j = 0; j <= rings; ++j) {
    const float theta = glm::pi<float>() * static_cast<float>(j) / static_cast<float>(rings);
    for (int i = 0; i <= segments; ++i) {
      const float phi =
          2.0f * glm::pi<float>() * static_cast<float>(i) / static_cast<float>(segments);
      p.positions.emplace_back(std::sin(theta) * std::cos(phi), std::cos(theta),
                               -std::sin(theta) * std::sin(phi));
    }
  }
  for (int j = 0; j < rings; ++j) {
    for (int i = 0; i < segments; ++i) {
      const auto a = static_cast<uint32_t>(j * (segments + 1) + i);
      const auto b = a + static_cast<uint32_t>(segments + 1);
      p.indices.insert(p.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  }
  return p;
}

Scene sceneOf(std::vector<std::pair<Primitive, glm::mat4>> parts, bool doubleSided = false) {
  Scene s;
  Material m;
  m.doubleSided = doubleSided;
  s.materials.push_back(m);
  for (auto& [p, world] : parts) {
    p.material = 0;
    Mesh mesh;
    mesh.primitives.push_back(p);
    s.meshes.push_back(mesh);
    Instance inst;
    inst.mesh = static_cast<int>(s.meshes.size()) - 1;
    inst.world = world;
    s.instances.push_back(inst);
  }
  return s;
}

const glm::mat4 kIdentity{1.0f};

TEST(SelfVisibilityTest, OneConvexBodyOrOnePlaneSeesNothingOfItself) {
  EXPECT_FALSE(surfacesSeeEachOther(sceneOf({{cube(), kIdentity}})));
  EXPECT_FALSE(surfacesSeeEachOther(sceneOf({{square(), kIdentity}})));
  EXPECT_FALSE(surfacesSeeEachOther(sceneOf({{uvSphere(32), kIdentity}})));
  // Placed anywhere, scaled and turned.
  const glm::mat4 placed =
      glm::rotate(glm::translate(kIdentity, {3, -2, 7}), 0.7f, glm::vec3(1, 2, 3)) *
      glm::scale(kIdentity, glm::vec3(40.0f, 2.0f, 0.5f));
  EXPECT_FALSE(surfacesSeeEachOther(sceneOf({{cube(), placed}})));
  // A double-sided plane faces nothing either: every vertex lies on it.
  EXPECT_FALSE(surfacesSeeEachOther(sceneOf({{square(), kIdentity}}, /*doubleSided=*/true)));
  EXPECT_FALSE(surfacesSeeEachOther(Scene{}));
}

TEST(SelfVisibilityTest, AnythingThatFacesAnotherSurfaceSeesItself) {
  // A cube on a floor: the floor faces the cube.
  const glm::mat4 up = glm::translate(kIdentity, {0, 0.5f, 0});
  EXPECT_TRUE(surfacesSeeEachOther(sceneOf({{cube(), up}, {square(), kIdentity}})));
  // Two cubes side by side, and a cube seen from inside (its faces turned inward).
  EXPECT_TRUE(surfacesSeeEachOther(
      sceneOf({{cube(), kIdentity}, {cube(), glm::translate(kIdentity, {3, 0, 0})}})));
  Primitive inside = cube();
  for (size_t t = 0; t < inside.indices.size(); t += 3) {
    std::swap(inside.indices[t + 1], inside.indices[t + 2]);
  }
  EXPECT_TRUE(surfacesSeeEachOther(sceneOf({{inside, kIdentity}})));
  // A mirrored cube keeps its faces outward (the transform turns the winding): still convex;
  // a mirrored inward cube is the room again.
  const glm::mat4 mirror = glm::scale(kIdentity, glm::vec3(-1, 1, 1));
  EXPECT_FALSE(surfacesSeeEachOther(sceneOf({{cube(), mirror}})));
  EXPECT_TRUE(surfacesSeeEachOther(sceneOf({{inside, mirror}})));
  // A double-sided cube may be seen from inside.
  EXPECT_TRUE(surfacesSeeEachOther(sceneOf({{cube(), kIdentity}}, /*doubleSided=*/true)));
  // A sphere on a floor.
  EXPECT_TRUE(surfacesSeeEachOther(
      sceneOf({{uvSphere(16), glm::translate(kIdentity, {0, 1, 0})}, {square(), kIdentity}})));
  // Two squares facing each other.
  const glm::mat4 above =
      glm::rotate(glm::translate(kIdentity, {0, 1, 0}), glm::pi<float>(), glm::vec3(1, 0, 0));
  EXPECT_TRUE(surfacesSeeEachOther(sceneOf({{square(), kIdentity}, {square(), above}})));
}

TEST(SelfVisibilityTest, LargeOrBrokenScenesCountAsSeeingThemselves) {
  // More vertices than the test looks at: assumed to see itself, even a plane.
  Primitive big;
  const int side = 50;  // 2500 vertices
  for (int z = 0; z < side; ++z) {
    for (int x = 0; x < side; ++x) big.positions.emplace_back(x, 0, z);
  }
  big.indices = {0, static_cast<uint32_t>(side), 1};
  ASSERT_GT(big.positions.size(), static_cast<size_t>(kSelfVisibilityMaxVertices));
  EXPECT_TRUE(surfacesSeeEachOther(sceneOf({{big, kIdentity}})));
  // An index past the positions.
  Primitive broken = square();
  broken.indices.back() = 99;
  EXPECT_TRUE(surfacesSeeEachOther(sceneOf({{broken, kIdentity}})));
}

}  // namespace
}  // namespace penumbra
