// KHR_materials_transmission and KHR_materials_volume in the renderer: a clear thin surface
// is invisible, a tinted one tints what is behind it, transmission keeps the white furnace,
// Beer-Lambert attenuation follows the thickness in world units (the instance's scale), and
// rough transmission blurs what is behind it as the frames accumulate.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class TransmissionGLTest : public GlFixture {};

constexpr int kTransmissionSize = 48;

// A clear surface: white, no reflection (ior 1: F0 = 0), everything transmitted.
Material clearGlass() {
  Material m = lambert(glm::vec3(1.0f));
  m.roughnessFactor = 0.0f;
  m.ior = 1.0f;
  m.transmission = 1.0f;
  m.doubleSided = true;
  return m;
}

// A vertical square of side `size` at depth z, facing +Z.
Mesh paneMesh(float size, float z, int material) {
  Mesh m;
  Primitive p;
  const float h = size * 0.5f;
  p.positions = {{-h, -h, z}, {h, -h, z}, {h, h, z}, {-h, h, z}};
  p.normals.assign(4, glm::vec3(0, 0, 1));
  p.indices = {0, 1, 2, 0, 2, 3};
  p.material = material;
  for (auto& v : p.positions) p.bounds.extend(v);
  m.primitives.push_back(std::move(p));
  return m;
}

RenderSettings settings(int frames) {
  RenderSettings rs;
  rs.width = rs.height = kTransmissionSize;
  rs.progressive.frames = frames;
  rs.progressive.probeVolume = false;  // the transmitted light alone
  return rs;
}

// Mean RGB over the image's central square of side 2r.
glm::vec3 centre(const Image& img, int r) {
  glm::vec3 sum(0.0f);
  for (int y = kTransmissionSize / 2 - r; y < kTransmissionSize / 2 + r; ++y) {
    for (int x = kTransmissionSize / 2 - r; x < kTransmissionSize / 2 + r; ++x)
      sum += glm::vec3(img.pixel(x, y)[0], img.pixel(x, y)[1], img.pixel(x, y)[2]);
  }
  return sum / float(4 * r * r);
}

// Coloured boxes on a grey floor under a uniform sky, seen from the front, with or without a
// pane of `glass` between them and the camera.
Result<Image> boxesBehind(const std::optional<Material>& glass) {
  Scene s;
  s.materials.push_back(lambert(glm::vec3(0.5f)));
  s.materials.push_back(lambert(glm::vec3(0.8f, 0.3f, 0.1f)));
  s.materials.push_back(lambert(glm::vec3(0.1f, 0.4f, 0.8f)));
  s.meshes.push_back(quadMesh(6.0f, -1.0f, 0));
  s.meshes.push_back(boxMesh({-1.2f, -1.0f, -1.5f}, {-0.2f, 0.3f, -0.5f}, 1));
  s.meshes.push_back(boxMesh({0.1f, -1.0f, -1.0f}, {1.0f, 0.8f, 0.0f}, 2));
  if (glass) {
    s.materials.push_back(*glass);
    s.meshes.push_back(paneMesh(2.4f, 1.0f, 3));
  }
  finishScene(s);
  // The pane widens the scene's bounds: keep the occlusion distance they would set.
  RenderSettings rs = settings(16);
  rs.progressive.occlusionDistance = 1.5f;
  return renderRadiance(s, uniformEnvironment(glm::vec3(0.8f)),
                        lookAtCamera({0, 0.3f, 5}, {0, -0.2f, 0}, 30.0f), rs);
}

TEST_F(TransmissionGLTest, ClearThinSurfaceIsInvisible) {
  // Nothing reflected (ior 1), everything passed straight through, and no shadow: the image
  // is the one without the pane.
  auto without = boxesBehind(std::nullopt);
  auto with = boxesBehind(clearGlass());
  ASSERT_TRUE(without.ok()) << without.message();
  ASSERT_TRUE(with.ok()) << with.message();
  EXPECT_TRUE(
      matchesImage(*with, *without, {.maxAbs = 0.03, .meanAbs = 0.002}, "transmission_clear_pane"));
}

TEST_F(TransmissionGLTest, TintedThinSurfaceTintsWhatIsBehind) {
  // Thin-walled transmission multiplies what is behind by the base colour.
  Material tinted = clearGlass();
  tinted.baseColorFactor = glm::vec4(1.0f, 0.5f, 0.25f, 1.0f);
  auto without = boxesBehind(std::nullopt);
  auto with = boxesBehind(tinted);
  ASSERT_TRUE(without.ok()) << without.message();
  ASSERT_TRUE(with.ok()) << with.message();
  const glm::vec3 a = centre(*without, 8), b = centre(*with, 8);
  EXPECT_NEAR(b.r, a.r, 0.01f * a.r + 1e-3f);
  EXPECT_NEAR(b.g, 0.5f * a.g, 0.01f * a.g + 1e-3f);
  EXPECT_NEAR(b.b, 0.25f * a.b, 0.01f * a.b + 1e-3f);
}

TEST_F(TransmissionGLTest, TransmissionKeepsTheWhiteFurnace) {
  // A white glass sphere in a white sky: what the specular layer does not reflect passes
  // through and brings the sky back, so the sphere disappears, thin-walled or thick, smooth
  // or rough, at any index of refraction.
  for (float thickness : {0.0f, 2.0f}) {
    for (float rough : {0.0f, 0.5f}) {
      for (float ior : {1.5f, 2.5f}) {
        Material m = clearGlass();
        m.doubleSided = false;
        m.ior = ior;
        m.roughnessFactor = rough;
        m.thickness = thickness;
        Scene s;
        s.materials.push_back(m);
        s.meshes.push_back(sphereMesh({0, 0, 0}, 1.0f, 0, 96));
        finishScene(s);
        auto img = renderRadiance(s, uniformEnvironment(glm::vec3(1.0f)),
                                  lookAtCamera({0, 0, 4}, {0, 0, 0}, 20.0f), settings(8));
        ASSERT_TRUE(img.ok()) << img.message();
        const glm::vec3 c = centre(*img, 14);
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(c[k], 1.0f, 0.02f)
              << "thickness " << thickness << ", roughness " << rough << ", ior " << ior;
        }
      }
    }
  }
}

TEST_F(TransmissionGLTest, BeerLambertFollowsTheThicknessInWorldUnits) {
  // A slab with thickness t (mesh units), attenuation colour c at distance d, placed with
  // scale k: light through it keeps c^(t k / d).
  const glm::vec3 colour(0.5f, 0.8f, 1.0f);
  for (float k : {1.0f, 2.0f}) {
    Material m = clearGlass();
    m.thickness = 0.5f;
    m.attenuationDistance = 1.0f;
    m.attenuationColor = colour;
    Scene s;
    s.materials.push_back(m);
    s.meshes.push_back(paneMesh(2.0f, 0.0f, 0));
    finishScene(s);
    s.instances[0].world = glm::scale(glm::mat4(1.0f), glm::vec3(k));
    s.bounds = {s.bounds.min * k, s.bounds.max * k};
    auto img = renderRadiance(s, uniformEnvironment(glm::vec3(1.0f)),
                              lookAtCamera({0, 0, 10}, {0, 0, 0}, 5.0f), settings(4));
    ASSERT_TRUE(img.ok()) << img.message();
    const glm::vec3 c = centre(*img, 8);
    for (int i = 0; i < 3; ++i) {
      const float expected = std::pow(colour[i], 0.5f * k / 1.0f);
      EXPECT_NEAR(c[i], expected, 0.01f) << "scale " << k << ", channel " << i;
    }
  }
}

// Pixels of the middle row that are neither dark nor bright: the width of the edge between
// a black and a white half seen through a pane of the given roughness.
int edgeWidth(float roughness) {
  Material black = lambert(glm::vec3(0.0f)), white = lambert(glm::vec3(1.0f));
  black.unlit = white.unlit = true;
  Material glass = clearGlass();
  glass.roughnessFactor = roughness;
  Scene s;
  s.materials = {black, white, glass};
  Mesh left = paneMesh(4.0f, -2.0f, 0), right = paneMesh(4.0f, -2.0f, 1);
  for (auto& v : left.primitives[0].positions) v.x = std::min(v.x, 0.0f);
  for (auto& v : right.primitives[0].positions) v.x = std::max(v.x, 0.0f);
  s.meshes = {left, right, paneMesh(3.0f, 0.0f, 2)};
  for (Mesh& mesh : s.meshes) {
    mesh.primitives[0].bounds = {};
    for (auto& v : mesh.primitives[0].positions) mesh.primitives[0].bounds.extend(v);
  }
  finishScene(s);
  RenderSettings rs = settings(64);
  auto img = renderRadiance(s, uniformEnvironment(glm::vec3(0.0f)),
                            lookAtCamera({0, 0, 4}, {0, 0, -2}, 30.0f), rs);
  EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.message());
  if (!img.ok()) return -1;
  int n = 0;
  for (int x = 0; x < kTransmissionSize; ++x) {
    const float v = img->pixel(x, kTransmissionSize / 2)[0];
    if (v > 0.1f && v < 0.9f) ++n;
  }
  return n;
}

TEST_F(TransmissionGLTest, RoughTransmissionBlursWhatIsBehind) {
  // Smooth: the edge stays within the antialiasing's pixel or two. Rough: one microfacet
  // normal a frame spreads it over many pixels once the frames are averaged.
  const int sharp = edgeWidth(0.0f);
  const int blurred = edgeWidth(0.6f);
  EXPECT_GE(sharp, 0);
  EXPECT_LE(sharp, 2);
  EXPECT_GE(blurred, 6);
}

}  // namespace
}  // namespace penumbra::test
