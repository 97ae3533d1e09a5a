// KHR_materials_variants in the renderer: Renderer::setVariant shows a variant's materials
// exactly as a scene loaded with those materials would, switching back gives the default
// image again, and bad indices are one-line errors.
#include <gtest/gtest.h>

#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class VariantsGLTest : public GlFixture {};

// A sphere on a floor under a uniform sky; two variants: "green" turns the sphere green and
// "cut" gives the floor a MASK material with alpha below its cut-off (it disappears).
Scene variantScene() {
  Scene s;
  s.materials = {lambert({0.8f, 0.1f, 0.1f}), lambert({0.1f, 0.8f, 0.1f}),
                 lambert({0.6f, 0.6f, 0.6f}), lambert({0.6f, 0.6f, 0.6f})};
  s.materials[3].alphaMode = AlphaMode::Mask;
  s.materials[3].baseColorFactor.a = 0.1f;
  s.meshes.push_back(sphereMesh({0.0f, 0.5f, 0.0f}, 0.5f, 0, 32));
  s.meshes.push_back(quadMesh(4.0f, 0.0f, 2));
  s.variants = {"green", "cut"};
  s.meshes[0].primitives[0].variantMaterials = {1, 0};
  s.meshes[1].primitives[0].variantMaterials = {2, 3};
  finishScene(s);
  return s;
}

// The scene as a file without variants would give it: each primitive with `variant`'s material.
Scene withVariantMaterials(Scene s, int variant) {
  for (Mesh& m : s.meshes) {
    for (Primitive& p : m.primitives) {
      p.material = variantMaterial(p, variant);
      p.variantMaterials.clear();
    }
  }
  s.variants.clear();
  return s;
}

RenderSettings variantSettings() {
  RenderSettings s;
  s.width = 48;
  s.height = 40;
  s.progressive.frames = 8;
  return s;
}

// Renders with `variants` selected one after another on the same renderer (each converged),
// returning the last image.
Result<Image> renderVariants(const Scene& scene, std::initializer_list<int> variants) {
  auto r = Renderer::create();
  if (!r) return r.error();
  PN_TRY((*r)->setSettings(variantSettings()));
  PN_TRY((*r)->setScene(scene));
  PN_TRY((*r)->setEnvironment(uniformEnvironment(glm::vec3(1.0f))));
  (*r)->setCamera(lookAtCamera({0.0f, 1.5f, 3.0f}, {0.0f, 0.4f, 0.0f}, 45.0f));
  for (int v : variants) {
    PN_TRY((*r)->setVariant(v));
    while (!(*r)->converged()) {
      auto f = (*r)->step();
      if (!f) return f.error();
    }
  }
  return (*r)->readRadiance();
}

Result<Image> renderPlain(const Scene& scene) {
  return renderRadiance(scene, uniformEnvironment(glm::vec3(1.0f)),
                        lookAtCamera({0.0f, 1.5f, 3.0f}, {0.0f, 0.4f, 0.0f}, 45.0f),
                        variantSettings());
}

TEST_F(VariantsGLTest, AVariantLooksLikeTheSceneWithItsMaterials) {
  const Scene scene = variantScene();
  for (int v : {0, 1}) {
    auto switched = renderVariants(scene, {v});
    ASSERT_TRUE(switched.ok()) << switched.message();
    auto loaded = renderPlain(withVariantMaterials(scene, v));
    ASSERT_TRUE(loaded.ok()) << loaded.message();
    EXPECT_TRUE(matchesImage(*switched, *loaded, {1e-4, 1e-6}, "variant_" + std::to_string(v)))
        << scene.variants[static_cast<size_t>(v)];
  }
}

TEST_F(VariantsGLTest, SwitchingChangesThePictureAndBackRestoresIt) {
  const Scene scene = variantScene();
  auto original = renderPlain(scene);
  ASSERT_TRUE(original.ok()) << original.message();
  auto green = renderVariants(scene, {0});
  ASSERT_TRUE(green.ok()) << green.message();
  // The sphere fills the middle of the image: greener than red under "green".
  const float* before = original->pixel(24, 22);
  const float* after = green->pixel(24, 22);
  EXPECT_GT(before[0], before[1]);
  EXPECT_GT(after[1], after[0]);
  auto cut = renderVariants(scene, {1});
  ASSERT_TRUE(cut.ok()) << cut.message();
  EXPECT_GT(rmse(*cut, *original), 0.05) << "the floor cut away under \"cut\"";
  auto back = renderVariants(scene, {0, 1, -1});
  ASSERT_TRUE(back.ok()) << back.message();
  EXPECT_TRUE(matchesImage(*back, *original, {1e-4, 1e-6}, "variant_back"));
}

TEST_F(VariantsGLTest, BadIndicesAreErrors) {
  auto r = Renderer::create();
  ASSERT_TRUE(r.ok()) << r.message();
  auto none = (*r)->setVariant(0);
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.message().find("no scene"), std::string::npos) << none.message();
  ASSERT_TRUE((*r)->setScene(variantScene()).ok());
  for (int bad : {2, -2}) {
    auto st = (*r)->setVariant(bad);
    ASSERT_FALSE(st.ok()) << bad;
    EXPECT_NE(st.message().find("the scene has 2"), std::string::npos) << st.message();
  }
  EXPECT_TRUE((*r)->setVariant(1).ok());
}

}  // namespace
}  // namespace penumbra::test
