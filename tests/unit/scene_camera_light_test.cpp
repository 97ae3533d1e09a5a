// glTF cameras (file cameras, lookup, default framing), EXT_lights_area, KHR_lights_punctual
// and the extension policy.
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "scene_gltf_builder.h"

namespace penumbra::test {
namespace {

using ::testing::HasSubstr;

const float kS45 = std::sqrt(0.5f);  // sin and cos of 45 degrees, for 90-degree quaternions

TEST(SceneGltfCamera, CamerasFromNodesWithoutScale) {
  GltfBuilder b;
  b.push("cameras",
         {{"name", "wide"},
          {"type", "perspective"},
          {"perspective", {{"yfov", 1.2}, {"znear", 0.1}, {"zfar", 50}, {"aspectRatio", 1.5}}}});
  b.push("cameras", {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.01}}}});
  b.push("cameras", {{"name", "ortho"},
                     {"type", "orthographic"},
                     {"orthographic", {{"xmag", 3}, {"ymag", 2}, {"znear", 0.1}, {"zfar", 10}}}});
  // Scaled and rotated 90 degrees about +Y: the camera looks down world -X.
  const int a = b.node({{"camera", 0},
                        {"translation", {0, 1, 5}},
                        {"rotation", {0, kS45, 0, kS45}},
                        {"scale", {2, 3, 4}}});
  const int c = b.node({{"camera", 1}, {"name", "nodecam"}});
  const int o = b.node({{"camera", 2}});
  b.scene({a, c, o});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->cameras.size(), 3u);
  EXPECT_FALSE(hasWarning(*scene, "orthographic"));

  const Camera& wide = scene->cameras[0];
  EXPECT_EQ(wide.name, "wide");
  EXPECT_FLOAT_EQ(wide.yfov, 1.2f);
  EXPECT_FLOAT_EQ(wide.aspect, 1.5f);
  EXPECT_FLOAT_EQ(wide.znear, 0.1f);
  EXPECT_FLOAT_EQ(wide.zfar, 50.0f);
  expectNear(glm::vec3(wide.world[3]), {0, 1, 5});
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(glm::length(glm::vec3(wide.world[i])), 1.0f, 1e-5f);
  expectNear(-glm::vec3(wide.world[2]), {-1, 0, 0});  // view direction
  expectNear(glm::vec3(wide.world[1]), {0, 1, 0});
  EXPECT_GT(glm::determinant(glm::mat3(wide.world)), 0.0f);

  const Camera& unnamed = scene->cameras[1];
  EXPECT_EQ(unnamed.name, "nodecam");  // falls back to the node's name
  EXPECT_EQ(unnamed.aspect, 0.0f);
  EXPECT_EQ(unnamed.zfar, 0.0f);
  EXPECT_FALSE(unnamed.orthographic);

  const Camera& ortho = scene->cameras[2];
  EXPECT_EQ(ortho.name, "ortho");
  EXPECT_TRUE(ortho.orthographic);
  EXPECT_FLOAT_EQ(ortho.ymag, 2.0f);
  EXPECT_FLOAT_EQ(ortho.aspect, 1.5f);  // xmag / ymag
  EXPECT_FLOAT_EQ(ortho.znear, 0.1f);
  EXPECT_FLOAT_EQ(ortho.zfar, 10.0f);

  auto byName = findCamera(*scene, "nodecam");
  ASSERT_TRUE(byName.ok()) << byName.message();
  EXPECT_EQ(*byName, 1);
  auto byIndex = findCamera(*scene, "0");
  ASSERT_TRUE(byIndex.ok()) << byIndex.message();
  EXPECT_EQ(*byIndex, 0);
  auto missing = findCamera(*scene, "tele");
  ASSERT_FALSE(missing.ok());
  EXPECT_THAT(missing.message(), HasSubstr("'tele'"));
  EXPECT_THAT(missing.message(), HasSubstr("wide"));
  EXPECT_THAT(missing.message(), HasSubstr("nodecam"));
  EXPECT_FALSE(findCamera(*scene, "7").ok());
  EXPECT_THAT(findCamera(Scene{}, "x").message(), HasSubstr("no cameras"));
}

TEST(SceneGltfCamera, OrthographicCameraNeedsAPositiveExtentAndDepthRange) {
  for (const auto& bad : {nlohmann::json{{"xmag", 1}, {"ymag", 0}, {"znear", 0}, {"zfar", 1}},
                          nlohmann::json{{"xmag", 1}, {"ymag", 1}, {"znear", 2}, {"zfar", 1}},
                          nlohmann::json{{"xmag", 1}, {"ymag", 1}, {"znear", 0}}}) {
    GltfBuilder b;
    b.push("cameras", {{"type", "orthographic"}, {"orthographic", bad}});
    b.scene({b.node({{"camera", 0}})});
    auto scene = b.load();
    ASSERT_FALSE(scene.ok()) << bad.dump();
    EXPECT_THAT(scene.message(), HasSubstr("cameras[0].orthographic")) << scene.message();
  }
}

TEST(SceneGltfCamera, DefaultCameraLooksFromTheFrontSlightlyAbove) {
  GltfBuilder b;
  const int pos = b.vec3({{-1, 0, -1}, {3, 0, -1}, {3, 2, 1}});
  const int m = b.mesh({{"attributes", {{"POSITION", pos}}}});
  b.scene({b.node({{"mesh", m}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const Camera cam = defaultCamera(*scene);
  EXPECT_NEAR(cam.yfov, glm::radians(45.0f), 1e-6f);
  const glm::vec3 eye(cam.world[3]);
  const glm::vec3 forward = -glm::vec3(cam.world[2]);
  // From +Z, slightly above (the fit itself is camera_fit_test's).
  EXPECT_GT(eye.z, 1.0f);
  EXPECT_GT(forward.y, -0.5f);
  EXPECT_LT(forward.y, -0.1f);  // "slightly": well under 45 degrees
  EXPECT_NEAR(forward.x, 0.0f, 1e-5f);
  EXPECT_NEAR(glm::vec3(cam.world[1]).y, std::sqrt(1.0f - forward.y * forward.y), 1e-4f);
  EXPECT_GT(cam.znear, 0.0f);
  for (const glm::vec3& p : {glm::vec3(-1, 0, -1), glm::vec3(3, 0, -1), glm::vec3(3, 2, 1)}) {
    EXPECT_LT(cam.znear, glm::dot(p - eye, forward));
  }

  // An empty scene still gives a usable camera.
  const Camera empty = defaultCamera(Scene{});
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) EXPECT_TRUE(std::isfinite(empty.world[c][r]));
  }
}

TEST(SceneGltfLight, AreaLightsRectAndDiskOnScaledRotatedNodes) {
  GltfBuilder b;
  b.useExtension("EXT_lights_area");
  b.doc["extensions"]["EXT_lights_area"]["lights"] = json::array({
      {{"name", "panel"},
       {"type", "rect"},
       {"color", {1, 0.5, 0.25}},
       {"intensity", 50},
       {"size", 0.5},
       {"rect", {{"aspect", 2}}}},
      {{"type", "disk"}},  // every default
      {{"name", "flat"}, {"type", "rect"}, {"size", 0}},
      {{"name", "negative"}, {"type", "disk"}, {"intensity", -3}},
  });
  // Rect: rotated -90 degrees about X (local -Z -> world -Y), scale (1, 3, 0.5).
  const int rect = b.node({{"name", "rectNode"},
                           {"translation", {0, 3, 0}},
                           {"rotation", {-kS45, 0, 0, kS45}},
                           {"scale", {1, 3, 0.5}},
                           {"extensions", {{"EXT_lights_area", {{"light", 0}}}}}});
  // Disk: under a parent mirrored and scaled by 2 in X.
  const int disk = b.node({{"name", "diskNode"},
                           {"translation", {0, 0, 1}},
                           {"extensions", {{"EXT_lights_area", {{"light", 1}}}}}});
  const int parent =
      b.node({{"translation", {1, 0, 0}}, {"scale", {-2, 1, 1}}, {"children", {disk}}});
  const int flat = b.node({{"extensions", {{"EXT_lights_area", {{"light", 2}}}}}});
  const int neg = b.node({{"extensions", {{"EXT_lights_area", {{"light", 3}}}}}});
  b.scene({rect, parent, flat, neg});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->lights.size(), 2u);
  EXPECT_TRUE(hasWarning(*scene, "'flat'"));
  EXPECT_TRUE(hasWarning(*scene, "'negative'"));

  const Light& r = scene->lights[0];
  EXPECT_EQ(r.name, "panel");
  EXPECT_EQ(r.type, LightType::Rect);
  EXPECT_TRUE(r.isArea());
  EXPECT_EQ(r.color, glm::vec3(1, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(r.intensity, 50.0f);
  expectNear(r.position, {0, 3, 0});
  expectNear(r.direction, {0, -1, 0});  // world -Z of the node
  expectNear(r.right, {1, 0, 0});
  expectNear(r.up, {0, 0, -1});
  // size x the largest world scale (3): width = 3 * 0.5 * aspect 2, height = 3 * 0.5.
  EXPECT_NEAR(r.width, 3.0f, 1e-5f);
  EXPECT_NEAR(r.height, 1.5f, 1e-5f);
  EXPECT_NEAR(r.area(), 4.5f, 1e-4f);

  const Light& d = scene->lights[1];
  EXPECT_EQ(d.name, "diskNode");  // unnamed light: the node's name
  EXPECT_EQ(d.type, LightType::Disk);
  EXPECT_EQ(d.color, glm::vec3(1.0f));
  EXPECT_FLOAT_EQ(d.intensity, 1000.0f);
  expectNear(d.position, {1, 0, 1});
  expectNear(d.direction, {0, 0, -1});
  expectNear(d.right, {-1, 0, 0});    // mirrored parent
  EXPECT_NEAR(d.width, 2.0f, 1e-5f);  // default size 1 x |scale| 2
  EXPECT_NEAR(d.height, 2.0f, 1e-5f);
  EXPECT_NEAR(d.area(), 3.14159265f, 1e-4f);
}

TEST(SceneGltfLight, LampProxiesCastNoShadow) {
  // A node marked extras.area_light_proxy is the visible face of an area light: drawn, but
  // blocking no light. Other nodes, and other extras, cast shadows as usual.
  GltfBuilder b;
  const int mesh = b.quadMesh();
  b.scene({b.node({{"mesh", mesh}, {"name", "lamp"}, {"extras", {{"area_light_proxy", 0}}}}),
           b.node({{"mesh", mesh}, {"name", "wall"}, {"extras", {{"note", "plain"}}}}),
           b.node({{"mesh", mesh}, {"name", "floor"}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->instances.size(), 3u);
  for (const Instance& i : scene->instances) {
    EXPECT_EQ(i.castsShadow, i.nodeName != "lamp") << i.nodeName;
  }
}

TEST(SceneGltfLight, PunctualLights) {
  GltfBuilder b;
  b.useExtension("KHR_lights_punctual");
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array({
      {{"name", "bulb"},
       {"type", "point"},
       {"color", {1, 0, 0}},
       {"intensity", 100},
       {"range", 10}},
      {{"name", "spot"},
       {"type", "spot"},
       {"intensity", 500},
       {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}},
      {{"name", "sun"}, {"type", "directional"}, {"intensity", 3}},
  });
  auto lightNode = [&](int i, json extra) {
    extra["extensions"] = {{"KHR_lights_punctual", {{"light", i}}}};
    return b.node(extra);
  };
  const int p = lightNode(0, {{"translation", {1, 2, 3}}});
  const int s = lightNode(1, {{"rotation", {kS45, 0, 0, kS45}}});  // +90 about X: -Z -> +Y
  const int sun = lightNode(2, json::object());
  b.scene({p, s, sun, b.node({{"mesh", b.quadMesh()}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->lights.size(), 3u);
  const Light& point = scene->lights[0];
  EXPECT_EQ(point.type, LightType::Point);
  EXPECT_FALSE(point.isArea());
  EXPECT_EQ(point.color, glm::vec3(1, 0, 0));
  EXPECT_FLOAT_EQ(point.intensity, 100.0f);
  EXPECT_FLOAT_EQ(point.range, 10.0f);
  expectNear(point.position, {1, 2, 3});
  const Light& spot = scene->lights[1];
  EXPECT_EQ(spot.type, LightType::Spot);
  EXPECT_FLOAT_EQ(spot.innerConeAngle, 0.2f);
  EXPECT_FLOAT_EQ(spot.outerConeAngle, 0.6f);
  EXPECT_EQ(spot.range, 0.0f);
  expectNear(spot.direction, {0, 1, 0});
  const Light& dir = scene->lights[2];
  EXPECT_EQ(dir.type, LightType::Directional);
  EXPECT_FLOAT_EQ(dir.intensity, 3.0f);
  expectNear(dir.direction, {0, 0, -1});
  EXPECT_TRUE(scene->warnings.empty());
}

// A spot on a child node turned -90 degrees about X, under a parent that is moved, turned about
// +Y and scaled unevenly (issue #60's spot that lit almost nothing): straight down from the
// parent's position, its cones and range as written.
TEST(SceneGltfLight, SpotOnARotatedChildPointsWhereItsNodeDoes) {
  GltfBuilder b;
  b.useExtension("KHR_lights_punctual");
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
      json::array({{{"type", "spot"},
                    {"intensity", 1000},
                    {"range", 25},
                    {"spot", {{"innerConeAngle", 0.353}, {"outerConeAngle", 0.393}}}}});
  const int spot = b.node({{"rotation", {-kS45, 0, 0, kS45}},
                           {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  const int rig = b.node({{"translation", {1, 4, 2}},
                          {"rotation", {0, kS45, 0, kS45}},
                          {"scale", {2, 1, 3}},
                          {"children", {spot}}});
  b.scene({rig, b.node({{"mesh", b.quadMesh()}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->lights.size(), 1u);
  const Light& l = scene->lights[0];
  expectNear(l.position, {1, 4, 2});
  expectNear(l.direction, {0, -1, 0});
  EXPECT_FLOAT_EQ(l.range, 25.0f);
  EXPECT_FLOAT_EQ(l.innerConeAngle, 0.353f);
  EXPECT_FLOAT_EQ(l.outerConeAngle, 0.393f);
  EXPECT_FLOAT_EQ(l.intensity, 1000.0f);
}

TEST(SceneGltfExtensions, RequiredUnknownExtensionIsAnError) {
  GltfBuilder b;
  b.useExtension("EXT_texture_webp", true);
  auto scene = b.load();
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.message(), "test.gltf: requires unsupported extension EXT_texture_webp");
}

TEST(SceneGltfExtensions, OptionalUnknownExtensionsWarn) {
  GltfBuilder b;
  b.useExtension("EXT_fancy_thing");
  b.useExtension("KHR_materials_pbrSpecularGlossiness");
  b.useExtension("KHR_materials_transmission");
  b.useExtension("KHR_materials_volume");
  b.useExtension("KHR_materials_sheen");
  b.useExtension("KHR_materials_clearcoat");
  b.useExtension("KHR_texture_transform");
  b.useExtension("KHR_mesh_quantization", true);
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  EXPECT_TRUE(hasWarning(*scene, "uses unsupported extension EXT_fancy_thing"));
  EXPECT_TRUE(hasWarning(*scene, "uses KHR_materials_pbrSpecularGlossiness, which is ignored"));
  EXPECT_FALSE(hasWarning(*scene, "KHR_materials_transmission"));
  EXPECT_FALSE(hasWarning(*scene, "KHR_materials_volume"));
  EXPECT_FALSE(hasWarning(*scene, "KHR_materials_clearcoat"));
  EXPECT_FALSE(hasWarning(*scene, "KHR_materials_sheen"));
  EXPECT_FALSE(hasWarning(*scene, "KHR_texture_transform"));
  EXPECT_FALSE(hasWarning(*scene, "KHR_mesh_quantization"));
}

}  // namespace
}  // namespace penumbra::test
