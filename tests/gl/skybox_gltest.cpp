// Renderer::setSkybox (model-viewer's skybox-image, issue #62): the view's background shows the
// skybox while the surfaces keep the light of the environment, and null brings the
// environment back as the background.
#include <gtest/gtest.h>

#include "gl_fixture.h"
#include "penumbra/environment.h"
#include "penumbra/renderer.h"
#include "render_fixture.h"

namespace penumbra::test {
namespace {

class SkyboxGLTest : public GlFixture {};

TEST_F(SkyboxGLTest, TheSkyboxIsSeenAndLightsNothing) {
  Scene scene;
  scene.materials.push_back(lambert(glm::vec3(0.8f)));
  scene.meshes.push_back(sphereMesh({0, 0, 0}, 1.0f, 0));
  finishScene(scene);
  RenderSettings rs;
  rs.width = rs.height = 48;
  rs.progressive.frames = 8;
  const Camera camera = lookAtCamera({0, 0, 4}, {0, 0, 0}, 40.0f);
  const PackedEnvironment white = uniformEnvironment(glm::vec3(1.0f));
  const PackedEnvironment red = uniformEnvironment(glm::vec3(0.5f, 0.0f, 0.0f));
  // skyboxes: applied in turn before rendering (null: back to the environment).
  const auto render = [&](std::vector<const PackedEnvironment*> skyboxes) -> Result<Image> {
    auto r = Renderer::create();
    if (!r) return r.error();
    PN_TRY((*r)->setSettings(rs));
    PN_TRY((*r)->setScene(scene));
    PN_TRY((*r)->setEnvironment(white));
    for (const PackedEnvironment* s : skyboxes) PN_TRY((*r)->setSkybox(s));
    (*r)->setCamera(camera);
    while (!(*r)->converged()) {
      auto f = (*r)->step();
      if (!f) return f.error();
    }
    return (*r)->readRadiance();
  };
  auto plain = render({});
  auto skybox = render({&red});
  auto back = render({&red, nullptr});
  ASSERT_TRUE(plain.ok() && skybox.ok() && back.ok());
  // A corner shows the background: the environment's white, or the skybox's red.
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(plain->pixel(1, 1)[c], 1.0f, 0.02f) << c;
    EXPECT_NEAR(skybox->pixel(1, 1)[c], c == 0 ? 0.5f : 0.0f, 0.02f) << c;
    EXPECT_NEAR(back->pixel(1, 1)[c], 1.0f, 0.02f) << c;
  }
  // The sphere keeps the white environment's light: the skybox lights nothing.
  for (int y = 18; y < 30; ++y) {
    for (int x = 18; x < 30; ++x) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(skybox->pixel(x, y)[c], plain->pixel(x, y)[c], 1e-3f) << x << "," << y;
      }
    }
  }
  EXPECT_GT(plain->pixel(24, 24)[1], 0.5f) << "the sphere is lit by the white environment";
}

}  // namespace
}  // namespace penumbra::test
