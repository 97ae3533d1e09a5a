// glTF animations posed at a time (scene/gltf_animation.cpp): each interpolation against its
// closed form, the ends held, rotations along the shortest arc, morph weights and skinned joints;
// a model posed at time t loads exactly as a file whose rest pose is that pose.
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "penumbra/animation.h"
#include "scene_gltf_builder.h"

namespace penumbra::test {
namespace {

using ::testing::HasSubstr;

int scalarAccessor(GltfBuilder& b, const std::vector<float>& v) {
  return b.accessor(b.view(v), kFloat, v.size(), "SCALAR");
}

// One mesh node "box" animated by `channel` of animation "move" (times 0, 1, 2 unless given).
GltfBuilder animatedBox(const std::string& path, const std::vector<float>& values,
                        const std::string& interpolation = "LINEAR",
                        const std::vector<float>& times = {0, 1, 2}) {
  GltfBuilder b;
  const int node = b.node({{"name", "box"}, {"mesh", b.quadMesh()}});
  b.scene({node});
  const int input = scalarAccessor(b, times);
  const char* type = path == "rotation" ? "VEC4" : "VEC3";
  const size_t width = path == "rotation" ? 4 : 3;
  const int output = b.accessor(b.view(values), kFloat, values.size() / width, type);
  b.push("animations",
         {{"name", "move"},
          {"samplers", {{{"input", input}, {"output", output}, {"interpolation", interpolation}}}},
          {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", path}}}}}}});
  return b;
}

glm::vec3 positionAt(GltfBuilder& b, float time, const std::string& animation = "move") {
  auto scene = b.load(false, {.animation = animation, .animationTime = time});
  EXPECT_TRUE(scene.ok()) << scene.message();
  return scene.ok() ? glm::vec3(scene->instances.at(0).world[3]) : glm::vec3(NAN);
}

void expectAt(glm::vec3 a, glm::vec3 e, const char* what) {
  EXPECT_LT(glm::length(a - e), 1e-4f) << what << ": " << a.x << " " << a.y << " " << a.z;
}

TEST(SceneAnimation, LinearAndStepTranslationsAndTheirEnds) {
  GltfBuilder linear = animatedBox("translation", {0, 0, 0, 2, 0, 0, 2, 4, 0});
  expectAt(positionAt(linear, 0.5f), {1, 0, 0}, "halfway to the second key");
  expectAt(positionAt(linear, 1.5f), {2, 2, 0}, "halfway to the third");
  expectAt(positionAt(linear, -1.0f), {0, 0, 0}, "before the first key: held");
  expectAt(positionAt(linear, 9.0f), {2, 4, 0}, "after the last: held");
  expectAt(positionAt(linear, 0.5f, "0"), {1, 0, 0}, "by index");
  // At rest without an animation asked for.
  auto rest = linear.load();
  ASSERT_TRUE(rest.ok());
  expectAt(glm::vec3(rest->instances[0].world[3]), {0, 0, 0}, "rest");
  ASSERT_EQ(rest->animations.size(), 1u);
  EXPECT_EQ(rest->animations[0].name, "move");
  EXPECT_FLOAT_EQ(rest->animations[0].duration, 2.0f);

  GltfBuilder step = animatedBox("translation", {0, 0, 0, 2, 0, 0, 2, 4, 0}, "STEP");
  expectAt(positionAt(step, 0.99f), {0, 0, 0}, "step holds the key before");
  expectAt(positionAt(step, 1.0f), {2, 0, 0}, "step at a key");
}

TEST(SceneAnimation, CubicSplineIsTheHermiteCurve) {
  // Keys at 0 and 2 (dt 2): in-tangent, value, out-tangent each; x goes 0 -> 1 with out-tangent
  // 0.5 at the first key and in-tangent 0 at the second. At u = 0.5: h01 + h10 dt 0.5 = 0.625.
  GltfBuilder b = animatedBox("translation",
                              {9, 9, 9, 0, 0, 0, 0.5f, 0, 0,  //
                               0, 0, 0, 1, 0, 0, 9, 9, 9},
                              "CUBICSPLINE", {0, 2});
  expectAt(positionAt(b, 1.0f), {0.625f, 0, 0}, "Hermite midpoint");
  expectAt(positionAt(b, 2.0f), {1, 0, 0}, "the last key's value, not its tangent");
}

TEST(SceneAnimation, RotationsSlerpAlongTheShortestArc) {
  const float h = std::sqrt(0.5f);
  // 0 -> 90 degrees about +Y, the second key written as the negated quaternion (the same
  // rotation): the shortest arc still passes 45 degrees, not 225.
  GltfBuilder b = animatedBox("rotation", {0, 0, 0, 1, 0, -h, 0, -h}, "LINEAR", {0, 1});
  auto scene = b.load(false, {.animation = "move", .animationTime = 0.5f});
  ASSERT_TRUE(scene.ok()) << scene.message();
  const glm::vec3 x(scene->instances[0].world[0]);
  expectAt(x, {std::cos(glm::radians(45.0f)), 0, -std::sin(glm::radians(45.0f))}, "x axis");
}

// A skinned quad whose joint moves, and a morphed quad whose weights change (animation "act";
// animated false: the same file with `jointAt` and `weight` as its rest pose and no animation).
GltfBuilder skinAndMorph(bool animated, glm::vec3 jointAt, float weight) {
  GltfBuilder b;
  const int pos = b.vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  const std::vector<uint8_t> joints(16, 0);
  const int ja = b.accessor(b.view(joints), kUByte, 4, "VEC4");
  const int wa = b.vec4({{1, 0, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}});
  const int skinned =
      b.mesh({{"attributes", {{"POSITION", pos}, {"JOINTS_0", ja}, {"WEIGHTS_0", wa}}},
              {"indices", b.indices16({0, 1, 2, 0, 2, 3})}});
  const int lift = b.vec3({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
  const int morphed = b.push("meshes", {{"primitives",
                                         {{{"attributes", {{"POSITION", pos}}},
                                           {"indices", b.indices16({0, 1, 2, 0, 2, 3})},
                                           {"targets", {{{"POSITION", lift}}}}}}},
                                        {"weights", {animated ? 0.0f : weight}}});
  const int joint =
      b.node({{"name", "joint"}, {"translation", {jointAt.x, jointAt.y, jointAt.z}}});
  b.push("skins", {{"joints", {joint}}});
  const int body = b.node({{"mesh", skinned}, {"skin", 0}});
  const int cube = b.node({{"mesh", morphed}, {"translation", {5, 0, 0}}});
  b.scene({joint, body, cube});
  if (animated) {
    const int times = scalarAccessor(b, {0, 1, 2});
    const int moves = b.vec3({{0, 0, 0}, {0, 2, 0}, {0, 2, 4}});
    const int weights = scalarAccessor(b, {0, 1, 0});
    b.push("animations",
           {{"name", "act"},
            {"samplers",
             {{{"input", times}, {"output", moves}}, {{"input", times}, {"output", weights}}}},
            {"channels",
             {{{"sampler", 0}, {"target", {{"node", joint}, {"path", "translation"}}}},
              {{"sampler", 1}, {"target", {{"node", cube}, {"path", "weights"}}}}}}});
  }
  return b;
}

TEST(SceneAnimation, PosedAtTIsTheFileWhoseRestPoseIsThatPose) {
  // A skinned quad whose joint moves, and a morphed quad whose weights change: loaded at time
  // 1.5 they match the same file with the sampled values written as its rest pose.
  auto posed =
      skinAndMorph(true, {0, 0, 0}, 0.0f).load(false, {.animation = "act", .animationTime = 1.5f});
  auto reference = skinAndMorph(false, {0, 2, 2}, 0.5f).load();
  ASSERT_TRUE(posed.ok()) << posed.message();
  ASSERT_TRUE(reference.ok()) << reference.message();
  ASSERT_EQ(posed->meshes.size(), reference->meshes.size());
  for (size_t m = 0; m < posed->meshes.size(); ++m) {
    const auto& a = posed->meshes[m].primitives.at(0).positions;
    const auto& e = reference->meshes[m].primitives.at(0).positions;
    ASSERT_EQ(a.size(), e.size());
    for (size_t v = 0; v < a.size(); ++v) expectAt(a[v], e[v], "vertex");
  }
  expectAt(posed->meshes[0].primitives[0].positions[2], {1, 3, 2}, "skinned vertex on the joint");
  EXPECT_NEAR(posed->meshes[1].primitives[0].positions[0].z, 0.5f, 1e-5f) << "half the lift";
}

// Playback (LoadOptions::playback): the rig posed at t and the primitives' rest data, morphed by
// the pose's weights and skinned by its joints as the loader does, give the still loaded at t;
// a still load keeps neither.
TEST(SceneAnimation, PlaybackRigPosesAsTheLoaderDoes) {
  GltfBuilder b = skinAndMorph(true, {0, 0, 0}, 0.0f);
  auto plain = b.load();
  ASSERT_TRUE(plain.ok()) << plain.message();
  EXPECT_FALSE(plain->rig);
  EXPECT_FALSE(plain->meshes.at(0).primitives.at(0).deformation);
  auto played = b.load(false, {.playback = true});
  ASSERT_TRUE(played.ok()) << played.message();
  ASSERT_TRUE(played->rig);
  const Rig& rig = *played->rig;
  ASSERT_EQ(rig.clips.size(), 1u);
  ASSERT_EQ(rig.meshes.size(), played->meshes.size());
  ASSERT_EQ(rig.instanceNode.size(), played->instances.size());
  for (float t : {0.25f, 1.5f, 3.0f}) {
    auto still = b.load(false, {.animation = "act", .animationTime = t});
    ASSERT_TRUE(still.ok()) << still.message();
    const Pose pose = poseRig(rig, 0, t);
    for (size_t i = 0; i < played->instances.size(); ++i) {
      for (int c = 0; c < 4; ++c) {
        expectAt(glm::vec3(pose.instanceWorld[i][c]), glm::vec3(still->instances[i].world[c]),
                 "instance world");
      }
    }
    for (size_t m = 0; m < played->meshes.size(); ++m) {
      const Deformation* d = played->meshes[m].primitives.at(0).deformation.get();
      ASSERT_NE(d, nullptr) << "mesh " << m << " is skinned or morphed";
      const std::vector<glm::vec3>& expected = still->meshes[m].primitives.at(0).positions;
      for (size_t v = 0; v < d->positions.size(); ++v) {
        glm::vec3 p = d->positions[v];
        const std::vector<float>& w = pose.weights[m];
        for (size_t k = 0; k < w.size() && k < d->targets.size(); ++k) {
          if (!d->targets[k].positions.empty()) p += w[k] * d->targets[k].positions[v];
        }
        if (rig.meshes[m].skin >= 0) {
          const auto& joints = pose.joints[static_cast<size_t>(rig.meshes[m].skin)];
          glm::mat4 s(0.0f);
          for (int k = 0; k < 4; ++k) {
            s += d->weights[v][k] * joints[static_cast<size_t>(d->joints[v][k])];
          }
          p = glm::vec3(s * glm::vec4(p, 1.0f));
        }
        expectAt(p, expected[v], "played vertex");
      }
    }
  }
}

// A crossfade's blend (PoseLayer): one layer is that clip's pose; two at half weight put a
// translation halfway between theirs and turn a rotation halfway along the arc.
TEST(SceneAnimation, PoseLayersBlendNodeByNode) {
  GltfBuilder moving = animatedBox("translation", {0, 0, 0, 2, 0, 0, 2, 4, 0});
  auto scene = moving.load(false, {.playback = true});
  ASSERT_TRUE(scene.ok()) << scene.message();
  const Rig& rig = *scene->rig;
  const PoseLayer one[] = {{0, 1.5f, 1.0f}};
  expectAt(glm::vec3(poseRig(rig, one).instanceWorld[0][3]), {2, 2, 0}, "one layer");
  const PoseLayer half[] = {{0, 1.0f, 0.5f}, {-1, 0.0f, 0.5f}};
  expectAt(glm::vec3(poseRig(rig, half).instanceWorld[0][3]), {1, 0, 0}, "half of (2, 0, 0)");
  const PoseLayer unweighted[] = {{0, 1.0f, 0.0f}, {0, 2.0f, 0.0f}};
  expectAt(glm::vec3(poseRig(rig, unweighted).instanceWorld[0][3]), {0, 0, 0}, "no weight: rest");
  // Rotations: 90 degrees about Y at t = 1, blended half with the rest pose: 45 degrees.
  const float s = std::sqrt(0.5f);
  GltfBuilder turning = animatedBox("rotation", {0, 0, 0, 1, 0, s, 0, s, 0, 1, 0, 0});
  auto turned = turning.load(false, {.playback = true});
  ASSERT_TRUE(turned.ok()) << turned.message();
  const glm::mat4 w = poseRig(*turned->rig, half).instanceWorld[0];
  expectAt(glm::vec3(w[0]), {std::cos(glm::radians(45.0f)), 0, -std::sin(glm::radians(45.0f))},
           "x axis turned 45 degrees");
}

TEST(SceneAnimation, BadRequestsAndFilesAreOneLineErrors) {
  GltfBuilder b = animatedBox("translation", {0, 0, 0, 2, 0, 0, 2, 4, 0});
  auto unknown = b.load(false, {.animation = "jump"});
  ASSERT_FALSE(unknown.ok());
  EXPECT_THAT(unknown.message(), HasSubstr("no animation 'jump'; available: 0: 'move'"));
  GltfBuilder none;
  none.scene({none.node({{"mesh", none.quadMesh()}})});
  auto noAnimations = none.load(false, {.animation = "0", .animationTime = 1.0f});
  ASSERT_FALSE(noAnimations.ok());
  EXPECT_THAT(noAnimations.message(), HasSubstr("the file has none"));
  // Two values for three times.
  GltfBuilder short_ = animatedBox("translation", {0, 0, 0, 2, 0, 0});
  auto mismatched = short_.load(false, {.animation = "move", .animationTime = 1.0f});
  ASSERT_FALSE(mismatched.ok());
  EXPECT_THAT(mismatched.message(), HasSubstr("do not match"));
  // A channel without a node (KHR_animation_pointer) is ignored with a warning.
  GltfBuilder pointer = animatedBox("translation", {0, 0, 0, 2, 0, 0, 2, 4, 0});
  pointer.doc["animations"][0]["channels"][0]["target"].erase("node");
  auto ignored = pointer.load(false, {.animation = "move", .animationTime = 1.0f});
  ASSERT_TRUE(ignored.ok()) << ignored.message();
  EXPECT_TRUE(hasWarning(*ignored, "ignored"));
}

}  // namespace
}  // namespace penumbra::test
