// KHR_materials_variants in the loader and the application layer: the root list of names, each
// primitive's material per variant (its own where a variant does not map it), lookup by name or
// index, the scene file's and the request's "variant", and one-line errors for bad indices.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "penumbra/render_job.h"
#include "scene_gltf_builder.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

// Two primitives (a quad each) and three materials; variants "red", "blue" and "plain":
// the first quad is material 0, red -> 1, blue -> 2; the second quad is material 2 and only
// "red" maps it (to 0); "plain" maps nothing.
GltfBuilder variantsGltf() {
  GltfBuilder b;
  b.useExtension("KHR_materials_variants");
  for (int i = 0; i < 3; ++i) b.push("materials", {{"name", "m" + std::to_string(i)}});
  b.doc["extensions"]["KHR_materials_variants"]["variants"] =
      json::array({{{"name", "red"}}, {{"name", "blue"}}, {{"name", "plain"}}});
  const int a = b.quadMesh(0), c = b.quadMesh(2);
  b.doc["meshes"][static_cast<size_t>(a)]["primitives"][0]["extensions"] = {
      {"KHR_materials_variants",
       {{"mappings",
         {{{"material", 1}, {"variants", {0}}}, {{"material", 2}, {"variants", {1}}}}}}}};
  b.doc["meshes"][static_cast<size_t>(c)]["primitives"][0]["extensions"] = {
      {"KHR_materials_variants", {{"mappings", {{{"material", 0}, {"variants", {0}}}}}}}};
  b.scene({b.node({{"mesh", a}}), b.node({{"mesh", c}, {"translation", {2, 0, 0}}})});
  return b;
}

TEST(SceneVariants, EachPrimitiveHasAMaterialPerVariant) {
  auto scene = variantsGltf().load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  for (const std::string& w : scene->warnings) {
    EXPECT_EQ(w.find("KHR_materials_variants"), std::string::npos) << w;
  }
  EXPECT_EQ(scene->variants, (std::vector<std::string>{"red", "blue", "plain"}));
  const Primitive& first = scene->meshes[0].primitives[0];
  const Primitive& second = scene->meshes[1].primitives[0];
  EXPECT_EQ(first.material, 0);
  EXPECT_EQ(first.variantMaterials, (std::vector<int>{1, 2, 0}));
  EXPECT_EQ(second.material, 2);
  EXPECT_EQ(second.variantMaterials, (std::vector<int>{0, 2, 2}));
  EXPECT_EQ(variantMaterial(first, -1), 0);
  EXPECT_EQ(variantMaterial(first, 1), 2);
  EXPECT_EQ(variantMaterial(second, 0), 0);
}

TEST(SceneVariants, FoundByNameOrIndex) {
  auto scene = variantsGltf().load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  EXPECT_EQ(*findVariant(*scene, "blue"), 1);
  EXPECT_EQ(*findVariant(*scene, "2"), 2);
  EXPECT_EQ(*findVariant(*scene, ""), -1);
  EXPECT_EQ(*findVariant(*scene, "default"), -1);
  auto bad = findVariant(*scene, "green");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.message(), "no variant 'green'; available: 0: 'red', 1: 'blue', 2: 'plain'");
  auto none = findVariant(Scene{}, "red");
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.message().find("the scene has no material variants"), std::string::npos);
}

TEST(SceneVariants, BadMappingsAreOneLineErrors) {
  const std::pair<json, const char*> cases[] = {
      {{{"mappings", {{{"material", 1}, {"variants", {3}}}}}}, "variants[0]"},
      {{{"mappings", {{{"material", 7}, {"variants", {0}}}}}}, "material"},
      {{{"mappings", {{{"material", 1}}}}}, "missing required 'variants'"},
      {{{"mappings", {5}}}, "must be an object"},
  };
  for (const auto& [ext, fragment] : cases) {
    GltfBuilder b = variantsGltf();
    b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"] = ext;
    auto scene = b.load();
    ASSERT_FALSE(scene.ok()) << ext.dump();
    EXPECT_NE(scene.message().find(fragment), std::string::npos) << scene.message();
    EXPECT_NE(scene.message().find("KHR_materials_variants"), std::string::npos) << scene.message();
    EXPECT_EQ(scene.message().find('\n'), std::string::npos);
  }
}

TEST(SceneVariants, RequestAndSceneFileChooseTheVariant) {
  const std::string dir = freshOutputDir("variants");
  const std::string gltf = dir + "/v.gltf";
  {
    std::ofstream(gltf) << variantsGltf().finalDoc(false).dump();
    std::ofstream(dir + "/v.json") << R"({"gltf": "v.gltf", "variant": "blue"})";
  }
  JobRequest req;
  req.scenePath = gltf;
  auto plain = RenderJob::load(req);
  ASSERT_TRUE(plain.ok()) << plain.message();
  EXPECT_EQ(plain->variant, -1);
  req.scenePath = dir + "/v.json";
  auto fromFile = RenderJob::load(req);
  ASSERT_TRUE(fromFile.ok()) << fromFile.message();
  EXPECT_EQ(fromFile->variant, 1);
  req.variant = "red";
  auto fromRequest = RenderJob::load(req);
  ASSERT_TRUE(fromRequest.ok()) << fromRequest.message();
  EXPECT_EQ(fromRequest->variant, 0);
  req.variant = "tartan";
  auto bad = RenderJob::load(req);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("no variant 'tartan'"), std::string::npos) << bad.message();
}

}  // namespace
}  // namespace penumbra::test
