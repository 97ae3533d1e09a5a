// EXT_mesh_gpu_instancing (scene/gltf_instancing.cpp): a node's mesh becomes one scene instance
// per copy, each with its TRANSLATION, ROTATION (float or normalized) and SCALE applied before
// the node's transform; the scene's bounds include every copy; malformed attributes are
// one-line errors.
#include <gtest/gtest.h>

#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "scene_gltf_builder.h"

namespace penumbra::test {
namespace {

bool hasWarning(const Scene& s, const std::string& part) {
  for (const std::string& w : s.warnings) {
    if (w.find(part) != std::string::npos) return true;
  }
  return false;
}

TEST(SceneInstancing, EveryCopyIsAnInstanceWithItsOwnTransform) {
  GltfBuilder b;
  b.useExtension("EXT_mesh_gpu_instancing", true);
  const int mesh = b.quadMesh();
  const int t = b.vec3({{0, 0, 0}, {10, 0, 0}, {0, 0, -5}});
  // ROTATION as normalized shorts: identity, 90 degrees about Y, 180 degrees about Z.
  const float h = std::sqrt(0.5f);
  const std::vector<int16_t> q = {
      0, 0, 0,     32767, 0, static_cast<int16_t>(h * 32767), 0, static_cast<int16_t>(h * 32767),
      0, 0, 32767, 0};
  const int r = b.accessor(b.view(q), 5122, 3, "VEC4", true);
  const int s = b.vec3({{1, 1, 1}, {2, 2, 2}, {1, 3, 1}});
  const int n =
      b.node({{"mesh", mesh},
              {"translation", {0, 1, 0}},
              {"extensions",
               {{"EXT_mesh_gpu_instancing",
                 {{"attributes", {{"TRANSLATION", t}, {"ROTATION", r}, {"SCALE", s}}}}}}}});
  b.scene({n});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  EXPECT_FALSE(hasWarning(*scene, "EXT_mesh_gpu_instancing"));
  ASSERT_EQ(scene->instances.size(), 3u);
  // Marked as copies of their node: the renderer draws them as one instanced draw.
  for (const Instance& inst : scene->instances) EXPECT_EQ(inst.copyOf, n);
  // The quad's corner (1, 1, 0) through each copy, then the node's translation (0, 1, 0).
  const auto corner = [&](size_t i) {
    return glm::vec3(scene->instances[i].world * glm::vec4(1, 1, 0, 1));
  };
  const auto near = [](glm::vec3 a, glm::vec3 e) { return glm::length(a - e) < 2e-3f; };
  EXPECT_TRUE(near(corner(0), {1, 2, 0}));
  EXPECT_TRUE(near(corner(1), {10, 3, -2})) << "scaled 2, turned 90 degrees about +Y";
  EXPECT_TRUE(near(corner(2), {-1, -2, -5})) << "scaled 3 in y, turned 180 degrees about Z";
  // The bounds take in every copy.
  EXPECT_LE(scene->bounds.min.z, -5.0f);
  EXPECT_GE(scene->bounds.max.x, 10.0f);
}

TEST(SceneInstancing, MalformedAttributesAreOneLineErrors) {
  const auto load = [](bool mismatch, bool integerRotation) {
    GltfBuilder b;
    b.useExtension("EXT_mesh_gpu_instancing");
    const int mesh = b.quadMesh();
    json attributes = {{"TRANSLATION", b.vec3({{0, 0, 0}, {1, 0, 0}})}};
    if (mismatch) attributes["SCALE"] = b.vec3({{1, 1, 1}});
    if (integerRotation) {
      const std::vector<int16_t> q = {0, 0, 0, 1, 0, 0, 0, 1};
      attributes["ROTATION"] = b.accessor(b.view(q), 5122, 2, "VEC4", false);
    }
    b.scene(
        {b.node({{"mesh", mesh},
                 {"extensions", {{"EXT_mesh_gpu_instancing", {{"attributes", attributes}}}}}})});
    return b.load();
  };
  auto counts = load(true, false);
  ASSERT_FALSE(counts.ok());
  EXPECT_NE(counts.message().find("nodes[0] EXT_mesh_gpu_instancing: SCALE has 1 instances"),
            std::string::npos)
      << counts.message();
  auto integer = load(false, true);
  ASSERT_FALSE(integer.ok());
  EXPECT_NE(integer.message().find("ROTATION: accessor"), std::string::npos) << integer.message();
  EXPECT_NE(integer.message().find("expected VEC4 float or normalized"), std::string::npos);
  EXPECT_EQ(integer.message().find('\n'), std::string::npos);
  auto fine = load(false, false);
  ASSERT_TRUE(fine.ok()) << fine.message();
  EXPECT_EQ(fine->instances.size(), 2u);
}

}  // namespace
}  // namespace penumbra::test

namespace penumbra::test {
namespace {

// A room's lamp: a 0.5 m area light (size 0.5, aspect 1) at (0, 2, 0), and emissive quads
// (the builder's unit quad, scaled) placed by `place`.
Result<Scene> lampScene(const std::vector<json>& places) {
  GltfBuilder b;
  b.useExtension("EXT_lights_area");
  b.doc["extensions"]["EXT_lights_area"]["lights"] =
      json::array({{{"name", "ceiling"}, {"type", "rect"}, {"intensity", 10}, {"size", 0.5}}});
  const int glowing = b.push("materials", {{"name", "glow"}, {"emissiveFactor", {1, 1, 1}}});
  const int plain = b.push("materials", {{"name", "plain"}});
  const int lamp = b.quadMesh(glowing);
  const int shade = b.quadMesh(plain);
  std::vector<int> roots = {b.node({{"name", "light"},
                                    {"translation", {0, 2, 0}},
                                    {"extensions", {{"EXT_lights_area", {{"light", 0}}}}}})};
  for (json place : places) {
    place["mesh"] = place.value("name", "") == "shade" ? shade : lamp;
    roots.push_back(b.node(place));
  }
  b.scene(roots);
  return b.load();
}

TEST(SceneLampFaces, AnEmissiveSurfaceOnAnAreaLightIsItsVisibleFace) {
  auto scene = lampScene({
      // The fitting's glowing panel around the light (a 0.5 m quad centred on it).
      {{"name", "fitting"}, {"translation", {-0.25, 1.75, 0}}, {"scale", {0.5, 0.5, 1}}},
      // An emissive sign across the room.
      {{"name", "sign"}, {"translation", {3, 1, 0}}, {"scale", {0.5, 0.5, 1}}},
      // An emissive wall that contains the light's position but is 16 times its size.
      {{"name", "wall"}, {"translation", {-4, -2, 0}}, {"scale", {8, 8, 1}}},
      // A plain (not emissive) quad on the light.
      {{"name", "shade"}, {"translation", {-0.25, 1.75, 0}}, {"scale", {0.5, 0.5, 1}}},
  });
  ASSERT_TRUE(scene.ok()) << scene.message();
  std::map<std::string, bool> lampFace;
  for (const Instance& i : scene->instances) lampFace[i.nodeName] = i.lampFace;
  EXPECT_TRUE(lampFace["fitting"]);
  EXPECT_FALSE(lampFace["sign"]) << "far from the light";
  EXPECT_FALSE(lampFace["wall"]) << "much larger than the light";
  EXPECT_FALSE(lampFace["shade"]) << "not emissive";
  EXPECT_TRUE(hasWarning(*scene,
                         "node 'fitting': its emissive surface sits on area light "
                         "'ceiling' and is taken as that light's visible face"));
  int warnings = 0;
  for (const std::string& w : scene->warnings)
    warnings += w.find("visible face") != std::string::npos;
  EXPECT_EQ(warnings, 1);
}

TEST(SceneLampFaces, TheRuleScalesWithTheScene) {
  // The same fitting in a scene a hundred times larger (centimetres): still found.
  GltfBuilder b;
  b.useExtension("EXT_lights_area");
  b.doc["extensions"]["EXT_lights_area"]["lights"] =
      json::array({{{"name", "ceiling"}, {"type", "rect"}, {"size", 50}}});
  const int glowing = b.push("materials", {{"emissiveFactor", {1, 1, 1}}});
  const int lamp = b.quadMesh(glowing);
  b.scene({b.node({{"translation", {0, 200, 0}},
                   {"extensions", {{"EXT_lights_area", {{"light", 0}}}}}}),
           b.node({{"name", "fitting"},
                   {"mesh", lamp},
                   {"translation", {-25, 175, 5}},
                   {"scale", {50, 50, 1}}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->instances.size(), 1u);
  EXPECT_TRUE(scene->instances[0].lampFace);
}

}  // namespace
}  // namespace penumbra::test
