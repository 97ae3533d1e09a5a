// KHR_materials_iridescence, _anisotropy, _diffuse_transmission and _dispersion in the loader:
// factors, their defaults and clamping, every texture in its slot, and tangents generated for
// an anisotropic material (its direction is given relative to the tangent).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "scene_gltf_builder.h"

namespace penumbra::test {
namespace {

TEST(SceneGltfLaterExtensions, FactorsTexturesAndDefaults) {
  GltfBuilder b;
  for (const char* e : {"KHR_materials_iridescence", "KHR_materials_anisotropy",
                        "KHR_materials_diffuse_transmission", "KHR_materials_dispersion"})
    b.useExtension(e);
  auto ext = [&](json e) { b.push("materials", {{"extensions", e}}); };
  ext({{"KHR_materials_iridescence",  // 0: factors
        {{"iridescenceFactor", 0.7},
         {"iridescenceIor", 1.8},
         {"iridescenceThicknessMinimum", 50},
         {"iridescenceThicknessMaximum", 700}}},
       {"KHR_materials_anisotropy", {{"anisotropyStrength", 0.6}, {"anisotropyRotation", 1.0}}},
       {"KHR_materials_diffuse_transmission",
        {{"diffuseTransmissionFactor", 0.4}, {"diffuseTransmissionColorFactor", {1.0, 0.5, 0.2}}}},
       {"KHR_materials_dispersion", {{"dispersion", 0.75}}}});
  ext({{"KHR_materials_iridescence",  // 1: out of range, every texture
        {{"iridescenceFactor", 2.0},
         {"iridescenceIor", 0.5},
         {"iridescenceTexture", {{"index", 0}}},
         {"iridescenceThicknessTexture", {{"index", 0}, {"texCoord", 1}}}}},
       {"KHR_materials_anisotropy",
        {{"anisotropyStrength", -1.0}, {"anisotropyTexture", {{"index", 0}}}}},
       {"KHR_materials_diffuse_transmission",
        {{"diffuseTransmissionFactor", 1.5},
         {"diffuseTransmissionColorFactor", {2.0, -1.0, 0.5}},
         {"diffuseTransmissionTexture", {{"index", 0}}},
         {"diffuseTransmissionColorTexture", {{"index", 0}}}}},
       {"KHR_materials_dispersion", {{"dispersion", -2.0}}}});
  ext({{"KHR_materials_iridescence", json::object()},  // 2: the extensions' defaults
       {"KHR_materials_anisotropy", json::object()},
       {"KHR_materials_diffuse_transmission", json::object()},
       {"KHR_materials_dispersion", json::object()}});
  b.push("images", {{"uri", "data:image/png;base64,AAAA"}});
  b.push("textures", {{"source", 0}});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const auto& m = scene->materials;
  ASSERT_EQ(m.size(), 3u);
  EXPECT_FLOAT_EQ(m[0].iridescence, 0.7f);
  EXPECT_FLOAT_EQ(m[0].iridescenceIor, 1.8f);
  EXPECT_FLOAT_EQ(m[0].iridescenceThicknessMin, 50.0f);
  EXPECT_FLOAT_EQ(m[0].iridescenceThicknessMax, 700.0f);
  EXPECT_FLOAT_EQ(m[0].anisotropy, 0.6f);
  EXPECT_FLOAT_EQ(m[0].anisotropyRotation, 1.0f);
  EXPECT_FLOAT_EQ(m[0].diffuseTransmission, 0.4f);
  EXPECT_EQ(m[0].diffuseTransmissionColor, glm::vec3(1.0f, 0.5f, 0.2f));
  EXPECT_FLOAT_EQ(m[0].dispersion, 0.75f);
  EXPECT_EQ(m[0].iridescenceTexture.image, -1);

  EXPECT_FLOAT_EQ(m[1].iridescence, 1.0f);
  EXPECT_FLOAT_EQ(m[1].iridescenceIor, 1.0f);
  EXPECT_FLOAT_EQ(m[1].anisotropy, 0.0f);
  EXPECT_FLOAT_EQ(m[1].diffuseTransmission, 1.0f);
  EXPECT_EQ(m[1].diffuseTransmissionColor, glm::vec3(1.0f, 0.0f, 0.5f));
  EXPECT_FLOAT_EQ(m[1].dispersion, 0.0f);
  for (TextureSlot slot :
       {TextureSlot::Iridescence, TextureSlot::IridescenceThickness, TextureSlot::Anisotropy,
        TextureSlot::DiffuseTransmission, TextureSlot::DiffuseTransmissionColor})
    EXPECT_GE(m[1].texture(slot).image, 0) << textureSlotInfo(slot).path;
  EXPECT_EQ(m[1].iridescenceThicknessTexture.texCoord, 1);
  EXPECT_TRUE(textureSlotInfo(TextureSlot::DiffuseTransmissionColor).srgb);
  EXPECT_FALSE(textureSlotInfo(TextureSlot::Anisotropy).srgb);
  for (const char* w :
       {"materials[1].extensions.KHR_materials_iridescence.iridescenceFactor: outside [0, 1]",
        "iridescenceIor: below 1", "anisotropyStrength: outside [0, 1]",
        "diffuseTransmissionFactor: outside [0, 1]",
        "diffuseTransmissionColorFactor: outside [0, 1]", "dispersion: negative"})
    EXPECT_TRUE(hasWarning(*scene, w)) << w;

  EXPECT_FLOAT_EQ(m[2].iridescence, 0.0f);
  EXPECT_FLOAT_EQ(m[2].iridescenceIor, 1.3f);
  EXPECT_FLOAT_EQ(m[2].iridescenceThicknessMin, 100.0f);
  EXPECT_FLOAT_EQ(m[2].iridescenceThicknessMax, 400.0f);
  EXPECT_FLOAT_EQ(m[2].anisotropy, 0.0f);
  EXPECT_FLOAT_EQ(m[2].anisotropyRotation, 0.0f);
  EXPECT_FLOAT_EQ(m[2].diffuseTransmission, 0.0f);
  EXPECT_EQ(m[2].diffuseTransmissionColor, glm::vec3(1.0f));
  EXPECT_FLOAT_EQ(m[2].dispersion, 0.0f);
  for (const std::string& w : scene->warnings) {
    EXPECT_EQ(w.find("unsupported"), std::string::npos) << w;
    EXPECT_EQ(w.find("not sampled"), std::string::npos) << w;
  }
}

TEST(SceneGltfLaterExtensions, AnisotropyGetsTangentsWithoutANormalMap) {
  // The direction is relative to the tangent: a file without TANGENT gets them generated
  // from TEXCOORD_0 (the quad's u runs along +x), as for a normal map.
  GltfBuilder b;
  b.useExtension("KHR_materials_anisotropy");
  b.push("materials",
         {{"extensions", {{"KHR_materials_anisotropy", {{"anisotropyStrength", 0.5}}}}}});
  b.push("materials", json::object());
  b.scene({b.node({{"mesh", b.quadMesh(0)}}), b.node({{"mesh", b.quadMesh(1)}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->meshes.size(), 2u);
  const Primitive& aniso = scene->meshes[0].primitives[0];
  ASSERT_EQ(aniso.tangents.size(), aniso.positions.size());
  for (const glm::vec4& t : aniso.tangents) {
    EXPECT_NEAR(t.x, 1.0f, 1e-5f);
    EXPECT_NEAR(t.w, 1.0f, 1e-5f);
  }
  EXPECT_TRUE(scene->meshes[1].primitives[0].tangents.empty()) << "no anisotropy: none needed";
}

}  // namespace
}  // namespace penumbra::test
