// Every KHR_materials_* texture is sampled (gpu/gpu_scene.h: a layer of the material's texture
// array each): a material whose extension texture holds value t renders like the same material
// without the texture and with its factor times t. Colour layers are decoded from sRGB, layers of
// different sizes share one array, and each layer follows its own UV transform.
#include <gtest/gtest.h>

#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class ExtensionTexturesGLTest : public GlFixture {};

constexpr int kTexturesSize = 48;

// One image of w x h texels, all `texel`.
ImageData solid(int w, int h, std::array<uint8_t, 4> texel) {
  ImageData img;
  img.name = "solid";
  img.width = w;
  img.height = h;
  for (int i = 0; i < w * h; ++i) img.pixels.insert(img.pixels.end(), texel.begin(), texel.end());
  return img;
}

// Mean radiance of the central 16x16 pixels of a unit sphere under a uniform white sky (with
// a grey floor-like lower half for the transmissive cases to show), 8 frames.
glm::vec3 render(const Material& material, const std::vector<ImageData>& images,
                 const std::vector<SamplerDesc>& samplers = {}) {
  Scene s;
  s.images = images;
  s.samplers = samplers;
  s.materials.push_back(material);
  s.meshes.push_back(sphereMesh({0, 0, 0}, 1.0f, 0, 96));
  finishScene(s);
  RenderSettings rs;
  rs.width = rs.height = kTexturesSize;
  rs.progressive.frames = 8;
  auto img = renderRadiance(s, uniformEnvironment(glm::vec3(1.0f)),
                            lookAtCamera({0, 0, 4}, {0, 0, 0}, 25.0f), rs);
  EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.message());
  glm::vec3 sum(0.0f);
  if (!img.ok()) return sum;
  for (int y = 16; y < 32; ++y) {
    for (int x = 16; x < 32; ++x)
      sum += glm::vec3(img->pixel(x, y)[0], img->pixel(x, y)[1], img->pixel(x, y)[2]);
  }
  return sum / 256.0f;
}

void expectNear(glm::vec3 a, glm::vec3 b, const char* what) {
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(a[k], b[k], 0.01f * std::abs(b[k]) + 2e-3f) << what << " channel " << k;
}

// A black base without reflection: what shows is the extension's layer alone.
Material blackBase() {
  Material m = lambert(glm::vec3(0.0f));
  m.specularFactor = 0.0f;
  return m;
}

constexpr float k128 = 128.0f / 255.0f;
// sRGB byte 188 decodes to about 0.50 linear.
const float kSrgb188 = srgbToLinear(188.0f / 255.0f);

TEST_F(ExtensionTexturesGLTest, ClearcoatTexturesScaleTheirFactors) {
  Material m = blackBase();
  m.clearcoat = 1.0f;
  m.clearcoatRoughness = 1.0f;
  const glm::vec3 noTexture = render(m, {});
  m.clearcoatTexture.image = 0;           // .r: strength
  m.clearcoatRoughnessTexture.image = 1;  // .g: roughness, a 4x4 image beside a 1x1 one
  const glm::vec3 textured =
      render(m, {solid(1, 1, {128, 0, 0, 255}), solid(4, 4, {0, 64, 0, 255})});
  Material f = blackBase();
  f.clearcoat = k128;
  f.clearcoatRoughness = 64.0f / 255.0f;
  const glm::vec3 factors = render(f, {});
  expectNear(textured, factors, "clearcoat");
  EXPECT_GT(glm::abs(textured.g - noTexture.g), 0.1f * noTexture.g) << "the textures change it";
}

TEST_F(ExtensionTexturesGLTest, SheenTexturesScaleTheirFactorsFromSrgb) {
  Material m = blackBase();
  m.sheenColor = glm::vec3(1.0f);
  m.sheenRoughness = 1.0f;
  m.sheenColorTexture.image = 0;      // .rgb, sRGB
  m.sheenRoughnessTexture.image = 0;  // .a
  const glm::vec3 textured = render(m, {solid(2, 2, {188, 188, 0, 128})});
  Material f = blackBase();
  f.sheenColor = glm::vec3(kSrgb188, kSrgb188, 0.0f);
  f.sheenRoughness = k128;
  expectNear(textured, render(f, {}), "sheen");
  EXPECT_LT(textured.b, 1e-4f);
}

TEST_F(ExtensionTexturesGLTest, SpecularTexturesScaleTheirFactorsFromSrgb) {
  Material m = lambert(glm::vec3(0.0f));
  m.roughnessFactor = 0.4f;
  m.specularTexture.image = 0;       // .a
  m.specularColorTexture.image = 0;  // .rgb, sRGB
  const glm::vec3 textured = render(m, {solid(1, 1, {255, 188, 0, 128})});
  Material f = lambert(glm::vec3(0.0f));
  f.roughnessFactor = 0.4f;
  f.specularFactor = k128;
  f.specularColorFactor = glm::vec3(1.0f, kSrgb188, 0.0f);
  expectNear(textured, render(f, {}), "specular");
}

TEST_F(ExtensionTexturesGLTest, TransmissionAndThicknessTexturesScaleTheirFactors) {
  Material m = lambert(glm::vec3(0.8f));
  m.roughnessFactor = 0.3f;
  m.transmission = 1.0f;
  m.thickness = 1.0f;
  m.attenuationDistance = 0.5f;
  m.attenuationColor = glm::vec3(0.9f, 0.3f, 0.1f);
  const glm::vec3 noTexture = render(m, {});
  m.transmissionTexture.image = 0;  // .r
  m.thicknessTexture.image = 0;     // .g
  const glm::vec3 textured = render(m, {solid(1, 1, {128, 64, 0, 255})});
  Material f = m;
  f.transmissionTexture = f.thicknessTexture = TextureRef{};
  f.transmission = k128;
  f.thickness = 64.0f / 255.0f;
  expectNear(textured, render(f, {}), "transmission");
  EXPECT_GT(glm::abs(textured.b - noTexture.b), 0.05f * noTexture.b) << "the textures change it";
}

TEST_F(ExtensionTexturesGLTest, EachLayerFollowsItsOwnUvTransform) {
  // A 2x1 image, left texel 0, right 255, sampled nearest: the specular texture's transform
  // picks the right half, the specular colour's the left; one array holds both.
  SamplerDesc nearest;
  nearest.minFilter = nearest.magFilter = 9728;
  nearest.wrapS = nearest.wrapT = 33071;
  ImageData halves = solid(2, 1, {0, 0, 0, 0});
  for (int c = 0; c < 4; ++c) halves.pixels[4 + static_cast<size_t>(c)] = 255;
  const auto half = [](float offset) {
    return glm::mat3(0.5f, 0, 0, 0, 1, 0, offset, 0, 1);  // u' = 0.5 u + offset
  };
  Material m = lambert(glm::vec3(0.0f));
  m.roughnessFactor = 0.4f;
  m.specularTexture = {.image = 0, .sampler = 0, .transform = half(0.5f)};
  const glm::vec3 right = render(m, {halves}, {nearest});
  m.specularTexture.transform = half(0.0f);
  const glm::vec3 left = render(m, {halves}, {nearest});
  Material f = lambert(glm::vec3(0.0f));
  f.roughnessFactor = 0.4f;
  expectNear(right, render(f, {}), "specular 1 from the right texel");
  EXPECT_LT(left.g, 1e-3f) << "specular 0 from the left texel";
}

}  // namespace
}  // namespace penumbra::test
