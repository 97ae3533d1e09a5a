// RenderSettings::transparentBackground: the pixels the scene leaves are transparent, the
// displayed image's alpha is the scene's coverage (fractional at its anti-aliased edges), and
// the covered pixels look as they do over the drawn background. Bloom keeps the alpha.
#include <gtest/gtest.h>

#include "gl_fixture.h"
#include "penumbra/environment.h"
#include "penumbra/renderer.h"
#include "render_fixture.h"

namespace penumbra::test {
namespace {

class TransparentBackgroundGLTest : public GlFixture {};

Result<Image> renderDisplay(const Scene& scene, const RenderSettings& rs) {
  auto r = Renderer::create();
  if (!r) return r.error();
  PN_TRY((*r)->setSettings(rs));
  PN_TRY((*r)->setScene(scene));
  PN_TRY((*r)->setEnvironment(uniformEnvironment(glm::vec3(0.6f, 0.7f, 0.9f))));
  (*r)->setCamera(lookAtCamera({0, 0, 4}, {0, 0, 0}, 40.0f));
  while (!(*r)->converged()) {
    auto f = (*r)->step();
    if (!f) return f.error();
  }
  return (*r)->readDisplay();
}

TEST_F(TransparentBackgroundGLTest, AlphaIsTheScenesCoverage) {
  Scene scene;
  scene.materials.push_back(lambert(glm::vec3(0.8f, 0.5f, 0.3f)));
  scene.meshes.push_back(sphereMesh({0, 0, 0}, 1.0f, 0));
  finishScene(scene);
  RenderSettings rs;
  rs.width = rs.height = 48;
  rs.progressive.frames = 32;
  auto opaque = renderDisplay(scene, rs);
  rs.transparentBackground = true;
  auto clear = renderDisplay(scene, rs);
  rs.bloom = 0.3f;
  auto bloomed = renderDisplay(scene, rs);
  ASSERT_TRUE(opaque.ok()) << opaque.message();
  ASSERT_TRUE(clear.ok()) << clear.message();
  ASSERT_TRUE(bloomed.ok()) << bloomed.message();
  ASSERT_EQ(clear->channels, 4);
  int edges = 0;
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 48; ++x) {
      const float a = clear->pixel(x, y)[3];
      EXPECT_EQ(opaque->pixel(x, y)[3], 1.0f) << "opaque everywhere without: " << x << "," << y;
      if (a > 0.05f && a < 0.95f) ++edges;
      // Inside, the same colour as over the drawn background (the sphere's own light).
      const float dx = static_cast<float>(x) - 23.5f, dy = static_cast<float>(y) - 23.5f;
      if (dx * dx + dy * dy < 8.0f * 8.0f) {
        EXPECT_EQ(a, 1.0f) << x << "," << y;
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(clear->pixel(x, y)[c], opaque->pixel(x, y)[c], 2.5f / 255.0f) << x << "," << y;
        }
      }
    }
  }
  // The corners show nothing of the environment: alpha 0, with or without bloom.
  for (const auto& [x, y] : {std::pair{1, 1}, {46, 1}, {1, 46}, {46, 46}}) {
    EXPECT_EQ(clear->pixel(x, y)[3], 0.0f) << x << "," << y;
    EXPECT_EQ(bloomed->pixel(x, y)[3], 0.0f) << x << "," << y;
    EXPECT_GT(opaque->pixel(x, y)[2], 0.5f) << "the environment is drawn without";
  }
  EXPECT_EQ(bloomed->pixel(24, 24)[3], 1.0f);
  // The silhouette is anti-aliased: partly covered pixels along it (a circle of radius about
  // 11 pixels has about 70 edge pixels).
  EXPECT_GT(edges, 20);
}

}  // namespace
}  // namespace penumbra::test
