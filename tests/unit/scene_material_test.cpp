// glTF materials, textures, samplers and images.
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "penumbra/image.h"
#include "scene_gltf_builder.h"

namespace penumbra::test {
namespace {

using ::testing::HasSubstr;

std::vector<uint8_t> makePng(int w, int h, glm::vec4 color) {
  Image img(w, h, 4);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float* p = img.pixel(x, y);
      // A gradient in red so downscaling has something to average.
      p[0] = w > 1 ? static_cast<float>(x) / static_cast<float>(w - 1) * color.r : color.r;
      p[1] = color.g;
      p[2] = color.b;
      p[3] = color.a;
    }
  }
  auto png = encodePng(img);
  EXPECT_TRUE(png.ok()) << png.message();
  return png.ok() ? *png : std::vector<uint8_t>{};
}

std::string pngDataUri(int w, int h, glm::vec4 color) {
  return "data:image/png;base64," + base64(makePng(w, h, color));
}

TEST(SceneGltfMaterial, EveryMaterialFieldAndTextureTransform) {
  GltfBuilder b;
  b.push("images", {{"uri", pngDataUri(2, 2, {1, 0, 0, 1})}, {"name", "red"}});
  const auto green = makePng(1, 1, {0, 1, 0, 1});
  b.push("images", {{"bufferView", b.view(green)}, {"mimeType", "image/png"}});
  b.push("images", {{"uri", "missing_normal.png"}});
  b.push("images", {{"uri", pngDataUri(1, 1, {1, 1, 1, 1})}});  // unused: not decoded
  b.push("samplers",
         {{"magFilter", 9728}, {"minFilter", 9984}, {"wrapS", 33071}, {"wrapT", 33648}});
  b.push("textures", {{"source", 0}, {"sampler", 0}});
  b.push("textures", {{"source", 1}});
  b.push("textures", {{"source", 2}});
  b.useExtension("KHR_texture_transform");
  b.useExtension("KHR_materials_emissive_strength");
  const float halfPi = 1.57079633f;
  b.push("materials",
         {{"name", "full"},
          {"pbrMetallicRoughness",
           {{"baseColorFactor", {0.5, 0.25, 1.0, 0.75}},
            {"metallicFactor", 0.3},
            {"roughnessFactor", 0.6},
            {"baseColorTexture", {{"index", 0}, {"texCoord", 1}}},
            {"metallicRoughnessTexture", {{"index", 1}}}}},
          {"normalTexture", {{"index", 2}, {"scale", 0.5}}},
          {"occlusionTexture", {{"index", 1}, {"strength", 0.7}, {"texCoord", 1}}},
          {"emissiveTexture",
           {{"index", 0},
            {"extensions",
             {{"KHR_texture_transform",
               {{"offset", {0.5, 0.25}},
                {"rotation", halfPi},
                {"scale", {2, 3}},
                {"texCoord", 1}}}}}}},
          {"emissiveFactor", {1.0, 0.5, 0.25}},
          {"alphaMode", "MASK"},
          {"alphaCutoff", 0.3},
          {"doubleSided", true},
          {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 5.0}}}}}});
  b.scene({b.node({{"mesh", b.quadMesh(0)}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->materials.size(), 1u);
  const Material& m = scene->materials[0];
  EXPECT_EQ(m.name, "full");
  EXPECT_EQ(m.baseColorFactor, glm::vec4(0.5f, 0.25f, 1.0f, 0.75f));
  EXPECT_FLOAT_EQ(m.metallicFactor, 0.3f);
  EXPECT_FLOAT_EQ(m.roughnessFactor, 0.6f);
  EXPECT_EQ(m.emissiveFactor, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(m.emissiveStrength, 5.0f);
  EXPECT_FLOAT_EQ(m.normalScale, 0.5f);
  EXPECT_FLOAT_EQ(m.occlusionStrength, 0.7f);
  EXPECT_EQ(m.alphaMode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(m.alphaCutoff, 0.3f);
  EXPECT_TRUE(m.doubleSided);

  // Three images are used; the fourth is never decoded.
  ASSERT_EQ(scene->images.size(), 3u);
  ASSERT_TRUE(m.baseColorTexture.valid());
  const ImageData& red = scene->images[static_cast<size_t>(m.baseColorTexture.image)];
  EXPECT_EQ(red.name, "red");
  EXPECT_EQ(red.width, 2);
  EXPECT_EQ(red.height, 2);
  EXPECT_FALSE(red.placeholder);
  EXPECT_EQ(red.pixels[4], 255);  // texel (1,0): full red
  EXPECT_EQ(red.pixels[7], 255);
  EXPECT_EQ(m.baseColorTexture.texCoord, 1);
  EXPECT_EQ(m.baseColorTexture.sampler, 0);
  EXPECT_EQ(m.baseColorTexture.transform, glm::mat3(1.0f));

  const ImageData& greenImg = scene->images[static_cast<size_t>(m.metallicRoughnessTexture.image)];
  EXPECT_EQ(greenImg.pixels, (std::vector<uint8_t>{0, 255, 0, 255}));
  EXPECT_EQ(m.metallicRoughnessTexture.sampler, -1);
  EXPECT_EQ(m.metallicRoughnessTexture.texCoord, 0);
  EXPECT_EQ(m.occlusionTexture.image, m.metallicRoughnessTexture.image);
  EXPECT_EQ(m.occlusionTexture.texCoord, 1);

  // The missing normal map: a warning and a flat-normal placeholder, not an error.
  const ImageData& normal = scene->images[static_cast<size_t>(m.normalTexture.image)];
  EXPECT_TRUE(normal.placeholder);
  EXPECT_EQ(normal.pixels, (std::vector<uint8_t>{128, 128, 255, 255}));
  EXPECT_TRUE(hasWarning(*scene, "missing_normal.png"));

  // KHR_texture_transform: offset, rotation, scale as one matrix, and the texCoord override.
  EXPECT_EQ(m.emissiveTexture.texCoord, 1);
  const glm::vec3 uv = m.emissiveTexture.transform * glm::vec3(1, 0, 1);
  // scale -> (2, 0); rotate by pi/2 (u' = c u + s v, v' = -s u + c v) -> (0, -2); offset.
  EXPECT_NEAR(uv.x, 0.5f, 1e-5f);
  EXPECT_NEAR(uv.y, -1.75f, 1e-5f);
  EXPECT_NEAR(uv.z, 1.0f, 1e-6f);
  const glm::vec3 uv2 = m.emissiveTexture.transform * glm::vec3(0, 1, 1);
  EXPECT_NEAR(uv2.x, 0.5f + 3.0f, 1e-5f);
  EXPECT_NEAR(uv2.y, 0.25f, 1e-5f);

  ASSERT_EQ(scene->samplers.size(), 1u);
  EXPECT_EQ(scene->samplers[0].magFilter, 9728);
  EXPECT_EQ(scene->samplers[0].minFilter, 9984);
  EXPECT_EQ(scene->samplers[0].wrapS, 33071);
  EXPECT_EQ(scene->samplers[0].wrapT, 33648);

  // The normal-mapped primitive got tangents.
  EXPECT_EQ(scene->meshes[0].primitives[0].tangents.size(), 4u);
}

TEST(SceneGltfMaterial, DefaultsAndAlphaModes) {
  GltfBuilder b;
  b.push("materials", json::object());
  b.push("materials", {{"alphaMode", "BLEND"}});
  b.push("materials", {{"alphaMode", "MASK"}});
  b.push("materials", {{"alphaMode", "SHINY"}});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->materials.size(), 4u);
  const Material& d = scene->materials[0];
  EXPECT_EQ(d.alphaMode, AlphaMode::Opaque);
  EXPECT_EQ(d.baseColorFactor, glm::vec4(1.0f));
  EXPECT_EQ(d.metallicFactor, 1.0f);
  EXPECT_EQ(d.roughnessFactor, 1.0f);
  EXPECT_EQ(d.emissiveFactor, glm::vec3(0.0f));
  EXPECT_EQ(d.emissiveStrength, 1.0f);
  EXPECT_FALSE(d.doubleSided);
  EXPECT_FALSE(d.baseColorTexture.valid());
  EXPECT_EQ(scene->materials[1].alphaMode, AlphaMode::Blend);
  EXPECT_EQ(scene->materials[2].alphaMode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(scene->materials[2].alphaCutoff, 0.5f);
  EXPECT_EQ(scene->materials[3].alphaMode, AlphaMode::Opaque);
  EXPECT_TRUE(hasWarning(*scene, "SHINY"));
}

TEST(SceneGltfMaterial, IorSpecularClearcoatAndUnlitExtensions) {
  GltfBuilder b;
  b.useExtension("KHR_materials_ior");
  b.useExtension("KHR_materials_specular");
  b.useExtension("KHR_materials_unlit");
  b.useExtension("KHR_materials_clearcoat");
  auto ext = [&](json e) { b.push("materials", {{"extensions", e}}); };
  ext(json::object());                           // 0: defaults
  ext({{"KHR_materials_ior", {{"ior", 2.0}}}});  // 1
  ext({{"KHR_materials_ior", {{"ior", 0.5}}}});  // 2: below 1
  ext({{"KHR_materials_ior", {{"ior", 0.0}}}});  // 3: infinite
  ext({{"KHR_materials_specular",                // 4
        {{"specularFactor", 0.5}, {"specularColorFactor", {1.0, 0.0, 0.5}}}}});
  ext({{"KHR_materials_specular",  // 5: clamped, texture
        {{"specularFactor", 2.0}, {"specularTexture", {{"index", 0}}}}}});
  ext({{"KHR_materials_unlit", json::object()}});  // 6
  ext({{"KHR_materials_clearcoat",                 // 7
        {{"clearcoatFactor", 0.8},
         {"clearcoatRoughnessFactor", 1.5},
         {"clearcoatTexture", {{"index", 0}}},
         {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}}});
  b.push("images", {{"uri", "data:image/png;base64,AAAA"}});
  b.push("textures", {{"source", 0}});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const auto& m = scene->materials;
  ASSERT_EQ(m.size(), 8u);
  EXPECT_FLOAT_EQ(m[0].ior, 1.5f);
  EXPECT_NEAR(m[0].dielectricF0().x, 0.04f, 1e-6f);
  EXPECT_FALSE(m[0].unlit);
  EXPECT_NEAR(m[1].dielectricF0().y, 1.0f / 9.0f, 1e-6f);
  EXPECT_FLOAT_EQ(m[2].ior, 1.0f);
  EXPECT_EQ(m[2].dielectricF0(), glm::vec3(0.0f));
  EXPECT_TRUE(hasWarning(*scene, "materials[2].extensions.KHR_materials_ior.ior"));
  EXPECT_NEAR(m[3].dielectricF0().z, 1.0f, 1e-6f);
  const glm::vec3 f4 = m[4].dielectricF0();
  EXPECT_NEAR(f4.x, 0.02f, 1e-6f);
  EXPECT_EQ(f4.y, 0.0f);
  EXPECT_NEAR(f4.z, 0.01f, 1e-6f);
  EXPECT_FLOAT_EQ(m[5].specularFactor, 1.0f);
  EXPECT_TRUE(hasWarning(*scene, "specularFactor: outside [0, 1]"));
  // Extension textures are sampled (a layer of the material's texture array each).
  EXPECT_GE(m[5].specularTexture.image, 0);
  EXPECT_EQ(m[4].specularTexture.image, -1);
  EXPECT_FALSE(hasWarning(*scene, "not sampled"));
  EXPECT_TRUE(m[6].unlit);
  EXPECT_FLOAT_EQ(m[0].clearcoat, 0.0f);
  EXPECT_FLOAT_EQ(m[7].clearcoat, 0.8f);
  EXPECT_FLOAT_EQ(m[7].clearcoatRoughness, 1.0f);
  EXPECT_TRUE(hasWarning(*scene, "clearcoatRoughnessFactor: outside [0, 1]"));
  EXPECT_GE(m[7].clearcoatTexture.image, 0);
  EXPECT_EQ(&m[7].texture(TextureSlot::Clearcoat), &m[7].clearcoatTexture);
  // The coat's own normal map is sampled (the lighting shader's spare unit).
  EXPECT_FALSE(hasWarning(*scene, "clearcoatNormalTexture is not sampled"));
  EXPECT_GE(m[7].clearcoatNormalTexture.image, 0);
  EXPECT_FLOAT_EQ(m[7].clearcoatNormalScale, 0.5f);
  EXPECT_EQ(m[0].clearcoatNormalTexture.image, -1);
  // None of the three is reported as ignored.
  for (const std::string& w : scene->warnings) EXPECT_EQ(w.find("ignored"), std::string::npos) << w;
}

TEST(SceneGltfMaterial, SheenExtension) {
  GltfBuilder b;
  b.useExtension("KHR_materials_sheen");
  auto ext = [&](json e) { b.push("materials", {{"extensions", e}}); };
  ext(json::object());  // 0: no sheen
  ext({{"KHR_materials_sheen",
        {{"sheenColorFactor", {0.9, 0.5, 0.1}}, {"sheenRoughnessFactor", 0.4}}}});  // 1
  ext({{"KHR_materials_sheen",  // 2: clamped, textures
        {{"sheenColorFactor", {2.0, -1.0, 0.5}},
         {"sheenRoughnessFactor", 3.0},
         {"sheenColorTexture", {{"index", 0}}},
         {"sheenRoughnessTexture", {{"index", 0}}}}}});
  ext({{"KHR_materials_sheen", json::object()}});  // 3: the extension's defaults
  b.push("images", {{"uri", "data:image/png;base64,AAAA"}});
  b.push("textures", {{"source", 0}});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const auto& m = scene->materials;
  ASSERT_EQ(m.size(), 4u);
  EXPECT_EQ(m[0].sheenColor, glm::vec3(0.0f));
  EXPECT_EQ(m[1].sheenColor, glm::vec3(0.9f, 0.5f, 0.1f));
  EXPECT_FLOAT_EQ(m[1].sheenRoughness, 0.4f);
  EXPECT_EQ(m[2].sheenColor, glm::vec3(1.0f, 0.0f, 0.5f));
  EXPECT_FLOAT_EQ(m[2].sheenRoughness, 1.0f);
  EXPECT_TRUE(
      hasWarning(*scene, "materials[2].extensions.KHR_materials_sheen.sheenColorFactor: outside"));
  EXPECT_TRUE(hasWarning(*scene, "sheenRoughnessFactor: outside [0, 1]"));
  EXPECT_GE(m[2].sheenColorTexture.image, 0);
  EXPECT_GE(m[2].sheenRoughnessTexture.image, 0);
  EXPECT_EQ(m[1].sheenColorTexture.image, -1);
  EXPECT_FALSE(hasWarning(*scene, "not sampled"));
  EXPECT_EQ(m[3].sheenColor, glm::vec3(0.0f));
  EXPECT_FLOAT_EQ(m[3].sheenRoughness, 0.0f);
  for (const std::string& w : scene->warnings) EXPECT_EQ(w.find("ignored"), std::string::npos) << w;
}

TEST(SceneGltfMaterial, TransmissionAndVolumeExtensions) {
  GltfBuilder b;
  b.useExtension("KHR_materials_transmission");
  b.useExtension("KHR_materials_volume");
  auto ext = [&](json e) { b.push("materials", {{"extensions", e}}); };
  ext(json::object());                                                 // 0: none
  ext({{"KHR_materials_transmission", {{"transmissionFactor", 0.8}}},  // 1
       {"KHR_materials_volume",
        {{"thicknessFactor", 0.25},
         {"attenuationDistance", 2.0},
         {"attenuationColor", {0.9, 0.5, 0.2}}}}});
  ext({{"KHR_materials_transmission",  // 2: clamped, textures, bad volume values
        {{"transmissionFactor", 1.5}, {"transmissionTexture", {{"index", 0}}}}},
       {"KHR_materials_volume",
        {{"thicknessFactor", -1.0},
         {"attenuationDistance", -3.0},
         {"attenuationColor", {2.0, 0.5, -1.0}},
         {"thicknessTexture", {{"index", 0}}}}}});
  ext({{"KHR_materials_transmission", json::object()},  // 3: the extensions' defaults
       {"KHR_materials_volume", json::object()}});
  b.push("images", {{"uri", "data:image/png;base64,AAAA"}});
  b.push("textures", {{"source", 0}});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const auto& m = scene->materials;
  ASSERT_EQ(m.size(), 4u);
  EXPECT_EQ(m[0].transmission, 0.0f);
  EXPECT_EQ(m[0].thickness, 0.0f);
  EXPECT_FLOAT_EQ(m[1].transmission, 0.8f);
  EXPECT_FLOAT_EQ(m[1].thickness, 0.25f);
  EXPECT_FLOAT_EQ(m[1].attenuationDistance, 2.0f);
  EXPECT_EQ(m[1].attenuationColor, glm::vec3(0.9f, 0.5f, 0.2f));
  EXPECT_FLOAT_EQ(m[2].transmission, 1.0f);
  EXPECT_EQ(m[2].thickness, 0.0f);
  EXPECT_EQ(m[2].attenuationDistance, 0.0f);
  EXPECT_EQ(m[2].attenuationColor, glm::vec3(1.0f, 0.5f, 0.0f));
  EXPECT_TRUE(hasWarning(*scene, "transmissionFactor: outside [0, 1]"));
  EXPECT_GE(m[2].transmissionTexture.image, 0);
  EXPECT_TRUE(hasWarning(*scene, "thicknessFactor: negative"));
  EXPECT_TRUE(hasWarning(*scene, "attenuationDistance: not positive"));
  EXPECT_TRUE(hasWarning(*scene, "attenuationColor: outside [0, 1]"));
  EXPECT_GE(m[2].thicknessTexture.image, 0);
  EXPECT_EQ(m[1].thicknessTexture.image, -1);
  EXPECT_FALSE(hasWarning(*scene, "not sampled"));
  EXPECT_EQ(m[3].transmission, 0.0f);
  EXPECT_EQ(m[3].thickness, 0.0f);
  EXPECT_EQ(m[3].attenuationDistance, 0.0f);
  EXPECT_EQ(m[3].attenuationColor, glm::vec3(1.0f));
  for (const std::string& w : scene->warnings)
    EXPECT_EQ(w.find("unsupported"), std::string::npos) << w;
}

TEST(SceneGltfMaterial, Ktx2TexturesFallBackNatively) {
  // KHR_texture_basisu: the native build has no Basis Universal transcoder, so a texture takes
  // its fallback PNG (with a warning), a KTX2-only texture is left out (with a warning), and a
  // KTX2 image reached as a plain source is a placeholder. The browser build transcodes them
  // (web/tests/compressed.test.mjs).
  const std::string ktx2 = "data:image/ktx2;base64,q0tUWCAyMLsNChoKAAAAAA==";  // the identifier
  GltfBuilder b;
  b.useExtension("KHR_texture_basisu", true);
  b.push("images", {{"uri", pngDataUri(2, 2, {1, 0, 0, 1})}});    // 0: the fallback
  b.push("images", {{"uri", ktx2}, {"mimeType", "image/ktx2"}});  // 1
  b.push("textures", {{"source", 0}, {"extensions", {{"KHR_texture_basisu", {{"source", 1}}}}}});
  b.push("textures", {{"extensions", {{"KHR_texture_basisu", {{"source", 1}}}}}});
  b.push("textures", {{"source", 1}});
  for (int t = 0; t < 3; ++t) {
    b.push("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", t}}}}}});
  }
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const auto& m = scene->materials;
  ASSERT_EQ(m.size(), 3u);
  ASSERT_GE(m[0].baseColorTexture.image, 0);
  const ImageData& fallback = scene->images[static_cast<size_t>(m[0].baseColorTexture.image)];
  EXPECT_EQ(fallback.width, 2);
  EXPECT_FALSE(fallback.placeholder);
  EXPECT_EQ(m[1].baseColorTexture.image, -1);
  ASSERT_GE(m[2].baseColorTexture.image, 0);
  EXPECT_TRUE(scene->images[static_cast<size_t>(m[2].baseColorTexture.image)].placeholder);
  EXPECT_TRUE(hasWarning(*scene,
                         "textures[0]: KHR_texture_basisu (KTX2) is transcoded only by "
                         "the browser build"));
  EXPECT_TRUE(hasWarning(*scene, "using its fallback image"));
  EXPECT_TRUE(hasWarning(*scene, "textures[1]: KHR_texture_basisu (KTX2)"));
  EXPECT_TRUE(hasWarning(*scene, "it has no fallback image"));
  EXPECT_TRUE(hasWarning(*scene, "cannot decode KTX2 (this build has no KTX2 transcoder)"));
}

TEST(SceneGltfMaterial, Ktx2SourceMustBeAnImage) {
  GltfBuilder b;
  b.push("textures", {{"extensions", {{"KHR_texture_basisu", {{"source", 3}}}}}});
  auto scene = b.load();
  ASSERT_FALSE(scene.ok());
  EXPECT_THAT(scene.message(), HasSubstr("KHR_texture_basisu.source"));
}

TEST(SceneGltfMaterial, OversizedImagesAreHalvedUntilTheyFit) {
  GltfBuilder b;
  b.push("images", {{"uri", pngDataUri(8, 4, {1, 0.5f, 0, 1})}});
  b.push("textures", {{"source", 0}});
  b.push("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  LoadOptions options;
  options.maxTextureSize = 2;
  auto scene = b.load(false, options);
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->images.size(), 1u);
  EXPECT_EQ(scene->images[0].width, 2);
  EXPECT_EQ(scene->images[0].height, 1);
  EXPECT_EQ(scene->images[0].pixels.size(), 8u);
  EXPECT_TRUE(hasWarning(*scene, "downscaled to 2x1"));
  // Red is a gradient 0..1 over x: the left half averages low, the right half high.
  EXPECT_LT(scene->images[0].pixels[0], scene->images[0].pixels[4]);
}

TEST(SceneGltfMaterial, UndecodableOrMissingImagesBecomePlaceholders) {
  GltfBuilder b;
  b.push("images", {{"uri", "data:image/png;base64,AAAAAAAA"}});
  b.push("images", {{"uri", "no/such/texture.png"}});
  b.push("textures", {{"source", 0}});
  b.push("textures", {{"source", 1}});
  b.push("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                       {"emissiveTexture", {{"index", 1}}}});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->images.size(), 2u);
  for (const ImageData& img : scene->images) {
    EXPECT_TRUE(img.placeholder);
    EXPECT_EQ(img.pixels, (std::vector<uint8_t>{255, 255, 255, 255}));
  }
  EXPECT_TRUE(hasWarning(*scene, "image 0: cannot decode"));
  EXPECT_TRUE(hasWarning(*scene, "no/such/texture.png"));
  for (const auto& w : scene->warnings) EXPECT_THAT(w, HasSubstr("test.gltf: "));
}

TEST(SceneGltfMaterial, ImageOverTheMemoryBudgetIsAnError) {
  GltfBuilder b;
  b.push("images", {{"uri", pngDataUri(64, 64, {1, 1, 1, 1})}});
  b.push("textures", {{"source", 0}});
  b.push("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  LoadOptions options;
  options.memoryBudgetBytes = 8000;  // the 64x64 RGBA8 image needs 16 KiB
  auto scene = b.load(false, options);
  ASSERT_FALSE(scene.ok());
  EXPECT_THAT(scene.message(), HasSubstr("memory budget"));
  EXPECT_THAT(scene.message(), HasSubstr("image 0"));
}

TEST(SceneGltfMaterial, ExtensionTexturesShareOneSamplerWithAWarningWhenTheyDiffer) {
  // The extension textures are layers of one texture array (gpu/gpu_scene.h): one sampler.
  GltfBuilder b;
  b.useExtension("KHR_materials_sheen");
  b.useExtension("KHR_materials_clearcoat");
  b.push("images", {{"uri", "data:image/png;base64,AAAA"}});
  b.push("samplers", {{"magFilter", 9728}});
  b.push("textures", {{"source", 0}, {"sampler", 0}});
  b.push("textures", {{"source", 0}});
  b.push("materials", {{"extensions",
                        {{"KHR_materials_sheen",
                          {{"sheenColorFactor", {1, 1, 1}},
                           {"sheenColorTexture", {{"index", 0}}},
                           {"sheenRoughnessTexture", {{"index", 0}}}}}}}});
  b.push("materials", {{"extensions",
                        {{"KHR_materials_clearcoat",
                          {{"clearcoatFactor", 1},
                           {"clearcoatTexture", {{"index", 0}}},
                           {"clearcoatRoughnessTexture", {{"index", 1}}}}}}}});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  EXPECT_FALSE(hasWarning(*scene, "materials[0]: its extension textures use different samplers"));
  EXPECT_TRUE(hasWarning(*scene, "materials[1]: its extension textures use different samplers"));
  // Every slot's table entry names its glTF path, and the colour slots are the sRGB ones.
  int srgb = 0;
  for (int i = 0; i < kTextureSlotCount; ++i) {
    const TextureSlotInfo& info = textureSlotInfo(static_cast<TextureSlot>(i));
    EXPECT_NE(std::string(info.path).find("Texture"), std::string::npos) << info.path;
    srgb += info.srgb ? 1 : 0;
  }
  EXPECT_EQ(srgb, 5) << "base colour, emissive, sheen colour, specular colour, diffuse "
                        "transmission colour";
}

}  // namespace
}  // namespace penumbra::test
