// EXT_mesh_gpu_instancing in the renderer: a node's copies are drawn as one instanced draw per
// primitive in every pass (prepass, lighting, area and point shadow maps, probe captures), and
// the picture equals the same copies drawn one by one, rotated, scaled and mirrored ones
// included.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu/gpu_scene.h"
#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class InstancingGLTest : public GlFixture {};

// A floor and a box mesh copied nine times on a 3 x 3 grid, each copy turned, scaled unevenly
// and one mirrored, under an area light and a point light (both casting shadows) and a dim sky
// (the probe volume gathers the copies' bounce light). `asCopies` marks the box instances as
// copies of one node (one instanced draw); otherwise each is its own item.
Scene copiesScene(bool asCopies, int copies = 9) {
  Scene s;
  s.materials = {lambert(glm::vec3(0.7f)), lambert({0.8f, 0.2f, 0.1f})};
  s.meshes.push_back(quadMesh(6.0f, 0.0f, 0));
  s.meshes.push_back(boxMesh({-0.25f, 0.0f, -0.25f}, {0.25f, 0.5f, 0.25f}, 1));
  finishScene(s);  // the floor's and the box's instances, identity transforms
  s.instances.pop_back();
  for (int i = 0; i < copies; ++i) {
    const float x = static_cast<float>(i % 3 - 1) * 1.2f, z = static_cast<float>(i / 3 - 1) * 1.2f;
    glm::mat4 w = glm::translate(glm::mat4(1.0f), {x, 0.0f, z});
    w = glm::rotate(w, 0.4f * static_cast<float>(i), glm::vec3(0.0f, 1.0f, 0.0f));
    w = glm::scale(w, {1.0f + 0.15f * static_cast<float>(i % 4), 1.0f + 0.2f * (i % 3), 0.8f});
    if (i == 4) w = glm::scale(w, {-1.0f, 1.0f, 1.0f});  // mirrored: winding and normals turn
    Instance copy{1, w, "box", true};
    copy.copyOf = asCopies ? 7 : -1;
    s.instances.push_back(copy);
  }
  Light area;
  area.type = LightType::Rect;
  area.intensity = 8.0f;
  area.position = {0.3f, 2.5f, 0.2f};
  area.direction = {0.0f, -1.0f, 0.0f};
  area.up = {0.0f, 0.0f, -1.0f};
  area.width = area.height = 0.8f;
  s.lights.push_back(area);
  Light point;
  point.type = LightType::Point;
  point.intensity = 2.0f;
  point.position = {-2.0f, 1.2f, 1.5f};
  s.lights.push_back(point);
  // The bounds take in every copy (the loader does this for a file).
  Bounds b;
  for (const Instance& inst : s.instances) {
    for (const Primitive& p : s.meshes[static_cast<size_t>(inst.mesh)].primitives) {
      for (const glm::vec3& v : p.positions) b.extend(glm::vec3(inst.world * glm::vec4(v, 1.0f)));
    }
  }
  s.bounds = b;
  return s;
}

Result<Image> renderCopies(const Scene& scene) {
  RenderSettings rs;
  rs.width = 96;
  rs.height = 64;
  rs.progressive.frames = 16;
  rs.progressive.shadowMapSize = 256;
  return renderRadiance(scene, uniformEnvironment(glm::vec3(0.15f)),
                        lookAtCamera({0.0f, 3.2f, 4.2f}, {0.0f, 0.2f, 0.0f}, 45.0f), rs);
}

TEST_F(InstancingGLTest, CopiesOfANodeAreOneItemPerPrimitiveAndWinding) {
  auto gpu = GpuScene::create(copiesScene(true));
  ASSERT_TRUE(gpu.ok()) << gpu.message();
  // The floor, the eight unmirrored copies and the mirrored one (its winding differs).
  const auto& items = (*gpu)->opaque();
  ASSERT_EQ(items.size(), 3u);
  int boxes = 0, mirrored = 0;
  for (const DrawItem& item : items) {
    if (item.material != 1) continue;  // the floor
    boxes += item.copies;
    if (item.mirrored) mirrored += item.copies;
  }
  EXPECT_EQ(boxes, 9);
  EXPECT_EQ(mirrored, 1);
  auto separate = GpuScene::create(copiesScene(false));
  ASSERT_TRUE(separate.ok()) << separate.message();
  EXPECT_EQ((*separate)->opaque().size(), 10u);
  EXPECT_EQ((*gpu)->bounds().min, (*separate)->bounds().min);
  EXPECT_EQ((*gpu)->bounds().max, (*separate)->bounds().max);
}

TEST_F(InstancingGLTest, InstancedDrawsLookLikeTheCopiesDrawnOneByOne) {
  auto instanced = renderCopies(copiesScene(true));
  ASSERT_TRUE(instanced.ok()) << instanced.message();
  auto oneByOne = renderCopies(copiesScene(false));
  ASSERT_TRUE(oneByOne.ok()) << oneByOne.message();
  // The same geometry, lights and sample sequences: equal up to float rounding (the capture
  // faces of a mis-indexed copy change the mean by 6e-4, a shadow map without copies by 8e-3).
  EXPECT_TRUE(matchesImage(*instanced, *oneByOne, {1e-4, 1e-5}, "instancing_vs_items"));
  // Not trivially so: the copies (their shading, shadows and bounce light) change the picture.
  auto floorOnly = renderCopies(copiesScene(true, 0));
  ASSERT_TRUE(floorOnly.ok()) << floorOnly.message();
  EXPECT_GT(rmse(*instanced, *floorOnly), 0.05);
}

}  // namespace
}  // namespace penumbra::test
