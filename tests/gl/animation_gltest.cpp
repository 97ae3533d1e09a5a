// Animation playback (Renderer::setPose): a scene loaded for playback and posed on the GPU at
// time t renders as the still the loader poses on the CPU at t (LoadOptions::animation), for a
// skinned strip, a morphed quad and an animated node at three times, and for the sample
// models Fox (skin), CesiumMan (Draco skin), AnimatedMorphCube and MorphStressTest (morph
// targets) where ../shared has them. A pose is a
// function of the time alone, whatever was posed before.
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "../unit/scene_gltf_builder.h"
#include "penumbra/animation.h"
#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class AnimationGLTest : public GlFixture {};

// A strip of 2x6 vertices along +X skinned to two joints (the second at x = 1 bends about Z),
// a quad with a morph target that lifts a corner toward the camera (and turns its normal), on a
// node that moves up; one animation "act" over 2 s drives all three.
GltfBuilder animatedModel() {
  GltfBuilder b;
  std::vector<glm::vec3> pos, nrm;
  std::vector<glm::vec4> weights;
  for (int i = 0; i < 6; ++i) {
    const float x = 0.4f * static_cast<float>(i);
    for (float y : {0.0f, 0.3f}) {
      pos.push_back({x, y, 0.0f});
      nrm.push_back({0, 0, 1});
      const float w1 = glm::clamp(x - 0.6f, 0.0f, 0.8f) / 0.8f;
      weights.push_back({1.0f - w1, w1, 0, 0});
    }
  }
  std::vector<uint16_t> idx;
  for (uint16_t i = 0; i < 5; ++i) {
    const uint16_t a = static_cast<uint16_t>(2 * i);
    idx.insert(idx.end(), {a, static_cast<uint16_t>(a + 2), static_cast<uint16_t>(a + 3), a,
                           static_cast<uint16_t>(a + 3), static_cast<uint16_t>(a + 1)});
  }
  std::vector<uint8_t> joints;
  for (size_t v = 0; v < pos.size(); ++v) joints.insert(joints.end(), {0, 1, 0, 0});
  const int ja = b.accessor(b.view(joints), kUByte, pos.size(), "VEC4");
  // Coloured on the white sky, so that a pose shows.
  const int red = b.push("materials", {{"pbrMetallicRoughness",
                                        {{"baseColorFactor", {0.8, 0.1, 0.1, 1.0}},
                                         {"metallicFactor", 0.0}}}});
  const int strip = b.mesh({{"material", red},
                            {"attributes",
                             {{"POSITION", b.vec3(pos)},
                              {"NORMAL", b.vec3(nrm)},
                              {"JOINTS_0", ja},
                              {"WEIGHTS_0", b.vec4(weights)}}},
                            {"indices", b.indices16(idx)}});
  const int quadPos = b.vec3({{0, 0, 0}, {0.8f, 0, 0}, {0.8f, 0.8f, 0}, {0, 0.8f, 0}});
  const int quadNrm = b.vec3({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
  const int lift = b.vec3({{0, 0, 0}, {0, 0, 0}, {0, 0, 0.6f}, {0, 0, 0}});
  const int turn = b.vec3({{0, 0, 0}, {0.5f, 0, 0}, {0.5f, 0.5f, 0}, {0, 0, 0}});
  const int quad = b.push(
      "meshes", {{"primitives",
                  {{{"material", red},
                    {"attributes", {{"POSITION", quadPos}, {"NORMAL", quadNrm}}},
                    {"indices", b.indices16({0, 1, 2, 0, 2, 3})},
                    {"targets", {{{"POSITION", lift}, {"NORMAL", turn}}}}}}},
                 {"weights", {0.0f}}});
  const int root = b.node({{"name", "root"}});
  const int bend = b.node({{"name", "bend"}, {"translation", {1.0f, 0.0f, 0.0f}}});
  b.doc["nodes"][static_cast<size_t>(root)]["children"] = {bend};
  const glm::mat4 ib0(1.0f), ib1 = glm::translate(glm::mat4(1.0f), glm::vec3(-1, 0, 0));
  std::vector<float> ibm(32);
  std::memcpy(ibm.data(), &ib0[0][0], 64);
  std::memcpy(ibm.data() + 16, &ib1[0][0], 64);
  const int ibmAccessor = b.accessor(b.view(ibm), kFloat, 2, "MAT4");
  b.push("skins", {{"joints", {root, bend}}, {"inverseBindMatrices", ibmAccessor}});
  const int body = b.node({{"mesh", strip}, {"skin", 0}});
  const int card = b.node({{"mesh", quad}, {"translation", {2.4f, 0.0f, 0.0f}}});
  b.scene({root, body, card});
  const int times = b.accessor(b.view(std::vector<float>{0, 1, 2}), kFloat, 3, "SCALAR");
  const glm::quat q0(1, 0, 0, 0), q1 = glm::angleAxis(glm::radians(50.0f), glm::vec3(0, 0, 1)),
                  q2 = glm::angleAxis(glm::radians(-40.0f), glm::vec3(0, 0, 1));
  const int rotations = b.vec4({{q0.x, q0.y, q0.z, q0.w}, {q1.x, q1.y, q1.z, q1.w},
                                {q2.x, q2.y, q2.z, q2.w}});
  const int w = b.accessor(b.view(std::vector<float>{0, 1, 0.3f}), kFloat, 3, "SCALAR");
  const int moves = b.vec3({{2.4f, 0, 0}, {2.4f, 0.4f, 0}, {2.6f, 0.2f, 0}});
  b.push("animations",
         {{"name", "act"},
          {"samplers",
           {{{"input", times}, {"output", rotations}},
            {{"input", times}, {"output", w}},
            {{"input", times}, {"output", moves}, {"interpolation", "STEP"}}}},
          {"channels",
           {{{"sampler", 0}, {"target", {{"node", bend}, {"path", "rotation"}}}},
            {{"sampler", 1}, {"target", {{"node", card}, {"path", "weights"}}}},
            {{"sampler", 2}, {"target", {{"node", card}, {"path", "translation"}}}}}}});
  return b;
}

RenderSettings smallSettings() {
  RenderSettings s;
  s.width = 96;
  s.height = 64;
  s.progressive.frames = 8;
  return s;
}

// Renders `scene` (posed at `time` of animation 0 first when `time` is given) to convergence.
Result<Image> render(const Scene& scene, const Camera& camera, std::optional<float> time,
                     std::optional<float> before = std::nullopt) {
  auto r = Renderer::create();
  if (!r) return r.error();
  PN_TRY((*r)->setSettings(smallSettings()));
  PN_TRY((*r)->setScene(scene));
  PN_TRY((*r)->setEnvironment(uniformEnvironment(glm::vec3(1.0f))));
  (*r)->setCamera(camera);
  if (before) PN_TRY((*r)->setPose(0, *before));
  if (time) PN_TRY((*r)->setPose(0, *time));
  while (!(*r)->converged()) {
    auto f = (*r)->step();
    if (!f) return f.error();
  }
  return (*r)->readRadiance();
}

// Played at each time against the CPU-posed still of the same file and time. The two differ
// only by float rounding of the same sums (GPU against CPU): at most a few per cent of the
// radiance in a pixel, where an edge moves by a fraction of it.
void expectPlayedAsPosed(const std::function<Result<Scene>(const LoadOptions&)>& load,
                         const Camera& camera, std::initializer_list<float> times,
                         const std::string& name) {
  auto played = load({.playback = true});
  ASSERT_TRUE(played.ok()) << played.message();
  ASSERT_TRUE(played->rig) << "playback keeps the rig";
  for (float t : times) {
    auto still = load({.animation = "0", .animationTime = t});
    ASSERT_TRUE(still.ok()) << still.message();
    auto a = render(*played, camera, t, /*before=*/t * 0.5f + 0.37f);
    auto e = render(*still, camera, std::nullopt);
    ASSERT_TRUE(a.ok()) << a.message();
    ASSERT_TRUE(e.ok()) << e.message();
    EXPECT_TRUE(matchesImage(*a, *e, {.maxAbs = 0.25, .meanAbs = 0.004},
                             name + "_t" + std::to_string(static_cast<int>(t * 100))))
        << "at " << t << " s";
    // And the pose is not the rest pose: the test would pass on a renderer that ignored it.
    auto rest = render(*played, camera, std::nullopt);
    ASSERT_TRUE(rest.ok()) << rest.message();
    EXPECT_GT(rmse(*a, *rest), 0.01) << name << " at " << t << " s looks like the rest pose";
  }
}

TEST_F(AnimationGLTest, SkinMorphAndNodeMatchTheCpuPoseAtThreeTimes) {
  GltfBuilder b = animatedModel();
  expectPlayedAsPosed([&](const LoadOptions& o) { return b.load(false, o); },
                      lookAtCamera({1.6f, 0.4f, 4.0f}, {1.6f, 0.4f, 0.0f}, 40.0f),
                      {0.4f, 1.0f, 1.7f}, "animation_builder");
}

std::string sample(const std::string& model, const std::string& file) {
  const auto path =
      std::filesystem::path(sourceDir()) / ".." / "shared" / "gltf-sample-assets" / model / file;
  return std::filesystem::exists(path) ? path.string() : std::string();
}

// A sample model played at `times`, seen from its bounds' centre plus `eye` radii.
void expectSampleModel(const std::string& model, const std::string& file, glm::vec3 eye,
                       std::initializer_list<float> times, const std::string& name) {
  const std::string path = sample(model, file);
  if (path.empty()) GTEST_SKIP() << "../shared/gltf-sample-assets/" << model << " is not here";
  auto rest = loadGltf(path);
  ASSERT_TRUE(rest.ok()) << rest.message();
  const glm::vec3 c = rest->bounds.center();
  expectPlayedAsPosed([&](const LoadOptions& o) { return loadGltf(path, o); },
                      lookAtCamera(c + rest->bounds.radius() * eye, c, 40.0f), times, name);
}

TEST_F(AnimationGLTest, FoxSkinMatchesTheCpuPoseAtThreeTimes) {
  expectSampleModel("Fox", "Fox.glb", {2.2f, 0.3f, 0.8f}, {0.3f, 0.9f, 1.6f}, "animation_fox");
}

TEST_F(AnimationGLTest, MorphCubeMatchesTheCpuPoseAtThreeTimes) {
  expectSampleModel("AnimatedMorphCube_Quantized", "AnimatedMorphCube.gltf", {1.6f, 1.2f, 2.2f},
                    {0.5f, 1.2f, 2.5f}, "animation_morph_cube");
}

// Draco-compressed joints and weights, a textured skin.
TEST_F(AnimationGLTest, DracoCesiumManMatchesTheCpuPoseAtThreeTimes) {
  expectSampleModel("CesiumMan_Draco", "CesiumMan.gltf", {0.3f, 0.4f, 2.4f}, {0.4f, 1.1f, 1.8f},
                    "animation_cesium_man");
}

// Eight morph targets (MorphStressTest: its animation drives them all).
TEST_F(AnimationGLTest, MorphStressTestMatchesTheCpuPoseAtThreeTimes) {
  expectSampleModel("MorphStressTest", "MorphStressTest.glb", {0.2f, 1.2f, 2.2f},
                    {0.5f, 1.5f, 2.5f}, "animation_morph_stress");
}

TEST_F(AnimationGLTest, BadPosesAreOneLineErrors) {
  GltfBuilder b = animatedModel();
  auto still = b.load();
  ASSERT_TRUE(still.ok()) << still.message();
  auto r = Renderer::create();
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_FALSE((*r)->setPose(0, 0.5f).ok()) << "no scene";
  ASSERT_TRUE((*r)->setScene(*still).ok());
  auto noRig = (*r)->setPose(0, 0.5f);
  ASSERT_FALSE(noRig.ok());
  EXPECT_NE(noRig.message().find("playback"), std::string::npos) << noRig.message();
  auto played = b.load(false, {.playback = true});
  ASSERT_TRUE(played.ok()) << played.message();
  ASSERT_TRUE((*r)->setScene(*played).ok());
  EXPECT_FALSE((*r)->setPose(1, 0.5f).ok()) << "one animation only";
  EXPECT_FALSE((*r)->setPose(0, NAN).ok());
  EXPECT_TRUE((*r)->setPose(-1, 0.0f).ok()) << "the rest pose";
  const PoseLayer negative[] = {{0, 0.5f, -1.0f}};
  EXPECT_FALSE((*r)->setPose(negative).ok()) << "a negative weight";
  const PoseLayer fade[] = {{0, 0.5f, 0.7f}, {-1, 0.0f, 0.3f}};
  EXPECT_TRUE((*r)->setPose(fade).ok()) << "a crossfade toward the rest pose";
}

}  // namespace
}  // namespace penumbra::test
