// Morph targets and skins at rest (scene/gltf_morph.cpp, gltf_skin.cpp): the mesh's default
// weights, or its node's, pose the mesh once at load (sparse targets included), each node with
// its own weights getting its own copy; skins pose their meshes by their joints in world space.
#include <gtest/gtest.h>

#include "scene_gltf_builder.h"

namespace penumbra::test {
namespace {

// A quad whose one target lifts vertex 2 by (0, 0, 1) (a sparse accessor over zeros) and whose
// second target moves every vertex by (1, 0, 0).
int morphedQuad(GltfBuilder& b, const std::vector<float>& meshWeights) {
  const int pos = b.vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  const std::vector<uint8_t> idx = {2, 0, 0, 0};
  const std::vector<float> val = {0, 0, 1};
  const int iv = b.view(idx.data(), 1);
  const int vv = b.view(val);
  const int lift = b.accessor(-1, kFloat, 4, "VEC3");
  b.doc["accessors"][static_cast<size_t>(lift)]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", iv}, {"componentType", kUByte}}},
      {"values", {{"bufferView", vv}}}};
  const int shift = b.vec3({{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}});
  json prim = {{"attributes", {{"POSITION", pos}}},
               {"indices", b.indices16({0, 1, 2, 0, 2, 3})},
               {"targets", {{{"POSITION", lift}}, {{"POSITION", shift}}}}};
  return b.push("meshes", {{"primitives", {prim}}, {"weights", meshWeights}});
}

TEST(SceneMorph, DefaultWeightsPoseTheMeshAndNodeWeightsTheirOwnCopy) {
  GltfBuilder b;
  const int mesh = morphedQuad(b, {0.5f, 0.0f});
  b.scene({b.node({{"name", "rest"}, {"mesh", mesh}}), b.node({{"name", "again"}, {"mesh", mesh}}),
           b.node({{"name", "posed"}, {"mesh", mesh}, {"weights", {1.0, 0.25}}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->meshes.size(), 2u) << "one copy for the mesh's weights, one for the node's";
  EXPECT_EQ(scene->instances[0].mesh, scene->instances[1].mesh);
  EXPECT_NE(scene->instances[0].mesh, scene->instances[2].mesh);
  const Primitive& rest =
      scene->meshes[static_cast<size_t>(scene->instances[0].mesh)].primitives[0];
  const Primitive& posed =
      scene->meshes[static_cast<size_t>(scene->instances[2].mesh)].primitives[0];
  EXPECT_NEAR(rest.positions[2].z, 0.5f, 1e-6f);
  EXPECT_NEAR(rest.positions[0].x, 0.0f, 1e-6f);
  EXPECT_NEAR(posed.positions[2].z, 1.0f, 1e-6f);
  EXPECT_NEAR(posed.positions[0].x, 0.25f, 1e-6f);
  EXPECT_NEAR(posed.positions[1].x, 1.25f, 1e-6f);
  EXPECT_GE(rest.bounds.max.z, 0.5f) << "bounds follow the pose";
  // Generated normals follow the bent shape: the lifted corner tilts its triangle.
  EXPECT_GT(std::abs(rest.normals[2].x) + std::abs(rest.normals[2].y), 0.1f);
}

TEST(SceneMorph, ATargetOfAnotherLengthIsAOneLineError) {
  GltfBuilder b;
  const int pos = b.vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}});
  const int shortTarget = b.vec3({{0, 0, 1}, {0, 0, 1}});
  json prim = {{"attributes", {{"POSITION", pos}}}, {"targets", {{{"POSITION", shortTarget}}}}};
  const int mesh = b.push("meshes", {{"primitives", {prim}}, {"weights", {1.0}}});
  b.scene({b.node({{"mesh", mesh}})});
  auto scene = b.load();
  ASSERT_FALSE(scene.ok());
  EXPECT_NE(scene.message().find("mesh 0 primitive 0 target 0 POSITION has 2 elements but "
                                 "POSITION has 3"),
            std::string::npos)
      << scene.message();
}

TEST(SceneSkin, JointsPoseTheMeshInWorldSpace) {
  // A quad whose vertices 0 and 1 follow joint 0 and 2 and 3 joint 1 (half and half for 3);
  // joint 0 sits at (0, 0, 5), joint 1 at (0, 0, 5) turned 90 degrees about +Y under it. The
  // skinned node's own translation (100, 0, 0) does not apply, as glTF defines.
  GltfBuilder b;
  const int pos = b.vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  const std::vector<uint8_t> joints = {0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0};
  const int ja = b.accessor(b.view(joints), kUByte, 4, "VEC4");
  const int wa = b.vec4({{1, 0, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}, {0.5f, 0.5f, 0, 0}});
  json prim = {{"attributes", {{"POSITION", pos}, {"JOINTS_0", ja}, {"WEIGHTS_0", wa}}},
               {"indices", b.indices16({0, 1, 2, 0, 2, 3})}};
  const int mesh = b.mesh(prim);
  const float h = std::sqrt(0.5f);
  const int child = b.node({{"name", "j1"}, {"rotation", {0, h, 0, h}}});
  const int root = b.node({{"name", "j0"}, {"translation", {0, 0, 5}}, {"children", {child}}});
  b.push("skins", {{"joints", {root, child}}});
  const int skinned =
      b.node({{"name", "body"}, {"mesh", mesh}, {"skin", 0}, {"translation", {100, 0, 0}}});
  b.scene({root, skinned});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->instances.size(), 1u);
  EXPECT_EQ(scene->instances[0].world, glm::mat4(1.0f));
  const Primitive& p = scene->meshes[0].primitives[0];
  const auto near = [](glm::vec3 a, glm::vec3 e) { return glm::length(a - e) < 1e-4f; };
  EXPECT_TRUE(near(p.positions[0], {0, 0, 5}));
  EXPECT_TRUE(near(p.positions[1], {1, 0, 5}));
  // Joint 1: (x, y, z) -> (z, y, -x) about +Y, then (0, 0, 5): (1, 1, 0) -> (0, 1, 4).
  EXPECT_TRUE(near(p.positions[2], {0, 1, 4})) << p.positions[2].x << " " << p.positions[2].z;
  // Half and half: (0, 1, 0) under joint 0 is (0, 1, 5), under joint 1 (0, 1, 5) too.
  EXPECT_TRUE(near(p.positions[3], {0, 1, 5}));
  EXPECT_TRUE(scene->bounds.max.z >= 5.0f && scene->bounds.max.x < 50.0f)
      << "the node's translation is not applied";

  // A joint index past the skin's joints is a one-line error.
  GltfBuilder bad;
  const int bp = bad.vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}});
  const std::vector<uint8_t> bj = {0, 0, 0, 0, 7, 0, 0, 0, 0, 0, 0, 0};
  json bprim = {{"attributes",
                 {{"POSITION", bp},
                  {"JOINTS_0", bad.accessor(bad.view(bj), kUByte, 3, "VEC4")},
                  {"WEIGHTS_0", bad.vec4({{1, 0, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}})}}}};
  const int bm = bad.mesh(bprim);
  const int bjoint = bad.node({{"name", "joint"}});
  bad.push("skins", {{"joints", {bjoint}}});
  bad.scene({bjoint, bad.node({{"mesh", bm}, {"skin", 0}})});
  auto failed = bad.load();
  ASSERT_FALSE(failed.ok());
  EXPECT_NE(failed.message().find("JOINTS_0: vertex 1 names joint 7 of a skin with 1"),
            std::string::npos)
      << failed.message();
}

}  // namespace
}  // namespace penumbra::test
