// glTF loading: containers, hierarchy and transforms, topology, attributes, generated normals
// and tangents.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene_gltf_builder.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

using ::testing::HasSubstr;

void expectMatNear(const glm::mat4& a, const glm::mat4& b, float eps = 1e-5f) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r)
      EXPECT_NEAR(a[c][r], b[c][r], eps) << "column " << c << " row " << r;
  }
}

GltfBuilder indexedTriangle() {
  GltfBuilder b;
  const int pos = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int idx = b.indices16({0, 1, 2});
  const int m = b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
  b.scene({b.node({{"mesh", m}})});
  return b;
}

TEST(SceneGltf, LoadsGltfWithDataUriAndGlb) {
  for (bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "glb" : "gltf");
    auto scene = indexedTriangle().load(binary);
    ASSERT_TRUE(scene.ok()) << scene.message();
    ASSERT_EQ(scene->meshes.size(), 1u);
    ASSERT_EQ(scene->instances.size(), 1u);
    const Primitive& p = scene->meshes[0].primitives.at(0);
    EXPECT_EQ(p.positions.size(), 3u);
    EXPECT_EQ(p.indices, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(p.material, -1);
    expectNear(scene->bounds.min, {0, 0, 0});
    expectNear(scene->bounds.max, {1, 1, 0});
    EXPECT_EQ(scene->triangleCount(), 1u);
    EXPECT_TRUE(scene->warnings.empty());
  }
}

TEST(SceneGltf, LoadsExternalBinWithPercentEncodedUri) {
  GltfBuilder b = indexedTriangle();
  b.autoBuffer = false;
  b.doc["buffers"] = json::array({{{"byteLength", b.bin.size()}, {"uri", "tri%20data.bin"}}});
  const std::string dir = outputDir() + "/scene_external_bin";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/tri data.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(b.bin.data()),
             static_cast<std::streamsize>(b.bin.size()));
  std::ofstream(dir + "/tri.gltf") << b.gltf();
  auto scene = loadGltf(dir + "/tri.gltf");
  ASSERT_TRUE(scene.ok()) << scene.message();
  EXPECT_EQ(scene->triangleCount(), 1u);

  // A .glb file on disk loads through the same path.
  const auto glb = indexedTriangle().glb();
  std::ofstream(dir + "/tri.glb", std::ios::binary)
      .write(reinterpret_cast<const char*>(glb.data()), static_cast<std::streamsize>(glb.size()));
  auto fromGlb = loadGltf(dir + "/tri.glb");
  ASSERT_TRUE(fromGlb.ok()) << fromGlb.message();
  EXPECT_EQ(fromGlb->triangleCount(), 1u);
}

TEST(SceneGltf, FlattensHierarchyIntoWorldMatrices) {
  GltfBuilder b;
  const int m = b.quadMesh();
  // parent: translate (1,0,0), rotate 90 degrees about Y; child: translate (0,1,0), scale 2;
  // grandchild: translate (0,0,1).
  const float s = std::sqrt(0.5f);
  const int grandchild = b.node({{"mesh", m}, {"translation", {0, 0, 1}}, {"name", "gc"}});
  const int child = b.node(
      {{"mesh", m}, {"translation", {0, 1, 0}}, {"scale", {2, 2, 2}}, {"children", {grandchild}}});
  const int parent =
      b.node({{"translation", {1, 0, 0}}, {"rotation", {0, s, 0, s}}, {"children", {child}}});
  b.scene({parent});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->instances.size(), 2u);
  EXPECT_EQ(scene->meshes.size(), 1u);  // one mesh, instanced twice
  const glm::mat4 P = glm::translate(glm::mat4(1), {1, 0, 0}) *
                      glm::mat4_cast(glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 1, 0)));
  const glm::mat4 C = glm::translate(glm::mat4(1), {0, 1, 0}) * glm::scale(glm::mat4(1), {2, 2, 2});
  const glm::mat4 G = glm::translate(glm::mat4(1), {0, 0, 1});
  expectMatNear(scene->instances[0].world, P * C);
  expectMatNear(scene->instances[1].world, P * C * G);
  EXPECT_EQ(scene->instances[1].nodeName, "gc");
  // The grandchild's origin: P * C * (0,0,1) = P * (0,1,2) = (1,0,0) + rotY90(0,1,2) = (3,1,0).
  expectNear(glm::vec3(scene->instances[1].world * glm::vec4(0, 0, 0, 1)), {3, 1, 0});
  EXPECT_EQ(scene->triangleCount(), 4u);
  // World bounds include both instances.
  EXPECT_TRUE(scene->bounds.valid());
  expectNear(scene->bounds.max, {3, 3, 0}, 1e-4f);
}

TEST(SceneGltf, MatrixAndTrsGiveTheSameWorld) {
  const glm::vec3 t(1, 2, 3);
  const glm::quat q = glm::normalize(glm::quat(0.8f, 0.2f, -0.4f, 0.4f));
  const glm::vec3 sc(1, 2, 0.5f);
  const glm::mat4 m =
      glm::translate(glm::mat4(1), t) * glm::mat4_cast(q) * glm::scale(glm::mat4(1), sc);
  std::vector<float> flat(16);
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) flat[static_cast<size_t>(c * 4 + r)] = m[c][r];
  }
  GltfBuilder b;
  const int mesh = b.quadMesh();
  const int a = b.node({{"mesh", mesh}, {"matrix", flat}});
  const int trs = b.node({{"mesh", mesh},
                          {"translation", {t.x, t.y, t.z}},
                          {"rotation", {q.x, q.y, q.z, q.w}},
                          {"scale", {sc.x, sc.y, sc.z}}});
  b.scene({a, trs});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->instances.size(), 2u);
  expectMatNear(scene->instances[0].world, m);
  expectMatNear(scene->instances[1].world, m);
}

TEST(SceneGltf, OnlyTheDefaultSceneIsLoaded) {
  GltfBuilder b;
  const int mesh = b.quadMesh();
  const int n0 = b.node({{"mesh", mesh}, {"name", "in0"}});
  const int n1 = b.node({{"mesh", mesh}, {"name", "in1"}});
  const int n2 = b.node({{"mesh", mesh}, {"name", "in1b"}});
  b.doc["scenes"] = json::array({{{"nodes", {n0}}}, {{"nodes", {n1, n2}}}});
  b.doc["scene"] = 1;
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->instances.size(), 2u);
  EXPECT_EQ(scene->instances[0].nodeName, "in1");
  EXPECT_EQ(scene->instances[1].nodeName, "in1b");

  b.doc.erase("scene");  // no default: scene 0
  auto first = b.load();
  ASSERT_TRUE(first.ok()) << first.message();
  ASSERT_EQ(first->instances.size(), 1u);
  EXPECT_EQ(first->instances[0].nodeName, "in0");
}

TEST(SceneGltf, NonIndexedTrianglesGetSequentialIndicesAndFlatNormals) {
  GltfBuilder b;
  // Two triangles folded along the shared edge x = 0 (a tent): non-indexed, so flat.
  const int pos = b.vec3({{0, 0, 0}, {0, 0, 1}, {-1, 1, 0}, {0, 0, 1}, {0, 0, 0}, {1, 1, 0}});
  const int m = b.mesh({{"attributes", {{"POSITION", pos}}}});
  b.scene({b.node({{"mesh", m}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const Primitive& p = scene->meshes[0].primitives[0];
  EXPECT_EQ(p.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
  ASSERT_EQ(p.normals.size(), 6u);
  const glm::vec3 left = glm::normalize(glm::cross(glm::vec3(0, 0, 1), glm::vec3(-1, 1, 0)));
  const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0, 0, -1), glm::vec3(1, 1, -1)));
  for (int i = 0; i < 3; ++i) expectNear(p.normals[static_cast<size_t>(i)], left);
  for (int i = 3; i < 6; ++i) expectNear(p.normals[static_cast<size_t>(i)], right);
}

TEST(SceneGltf, IndexedMeshGetsAreaWeightedSmoothNormals) {
  GltfBuilder b;
  // The same tent, indexed: the shared edge's vertices average both faces.
  const int pos = b.vec3({{0, 0, 0}, {0, 0, 1}, {-1, 1, 0}, {1, 1, 0}});
  const int idx = b.indices16({0, 2, 1, 1, 3, 0});
  const int m = b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
  b.scene({b.node({{"mesh", m}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const Primitive& p = scene->meshes[0].primitives[0];
  ASSERT_EQ(p.normals.size(), 4u);
  // Equal areas: the ridge vertices get the average of (1,1,0)/√2 and (-1,1,0)/√2.
  expectNear(p.normals[0], {0, 1, 0});
  expectNear(p.normals[1], {0, 1, 0});
  expectNear(p.normals[2], glm::normalize(glm::vec3(1, 1, 0)));
  expectNear(p.normals[3], glm::normalize(glm::vec3(-1, 1, 0)));
}

TEST(SceneGltf, StripsAndFansBecomeTriangleLists) {
  GltfBuilder b;
  // A strip up a ladder in the XY plane, counter-clockwise as seen from +Z.
  const int stripPos = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}});
  const int strip = b.mesh({{"attributes", {{"POSITION", stripPos}}}, {"mode", 5}});
  // A fan around the origin.
  const int fanPos = b.vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}});
  const int fanIdx = b.indices16({0, 1, 2, 3, 4});
  const int fan =
      b.mesh({{"attributes", {{"POSITION", fanPos}}}, {"indices", fanIdx}, {"mode", 6}});
  b.scene({b.node({{"mesh", strip}}), b.node({{"mesh", fan}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const Primitive& s = scene->meshes[0].primitives[0];
  const Primitive& f = scene->meshes[1].primitives[0];
  EXPECT_EQ(s.indices.size(), 9u);
  EXPECT_EQ(f.indices, (std::vector<uint32_t>{1, 2, 0, 2, 3, 0, 3, 4, 0}));
  for (const Primitive* p : {&s, &f}) {
    for (size_t t = 0; t < p->indices.size(); t += 3) {
      const glm::vec3 n = glm::cross(p->positions[p->indices[t + 1]] - p->positions[p->indices[t]],
                                     p->positions[p->indices[t + 2]] - p->positions[p->indices[t]]);
      EXPECT_GT(n.z, 0.0f) << "triangle " << t / 3 << " is wound the wrong way";
    }
    for (const glm::vec3& n : p->normals) expectNear(n, {0, 0, 1});
  }
  // The non-indexed strip was unwelded so its generated normals are flat.
  EXPECT_EQ(s.positions.size(), 9u);
}

TEST(SceneGltf, PointsAndLinesAreSkippedWithAWarning) {
  GltfBuilder b;
  const int pos = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int idx = b.indices16({0, 1, 2});
  b.push("meshes", {{"primitives",
                     {{{"attributes", {{"POSITION", pos}}}, {"mode", 0}},
                      {{"attributes", {{"POSITION", pos}}}, {"mode", 1}},
                      {{"attributes", {{"POSITION", pos}}}, {"indices", idx}}}}});
  b.scene({b.node({{"mesh", 0}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  EXPECT_EQ(scene->meshes[0].primitives.size(), 1u);
  EXPECT_TRUE(hasWarning(*scene, "POINTS are not rendered"));
  EXPECT_TRUE(hasWarning(*scene, "LINES are not rendered"));
}

// Tangent frame checks shared by the tangent tests.
void expectOrthonormalFrames(const Primitive& p) {
  ASSERT_EQ(p.tangents.size(), p.positions.size());
  for (size_t v = 0; v < p.tangents.size(); ++v) {
    const glm::vec3 t(p.tangents[v]);
    EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(t, p.normals[v]), 0.0f, 1e-5f);
    EXPECT_EQ(std::fabs(p.tangents[v].w), 1.0f);
  }
}

TEST(SceneGltf, TangentsGeneratedWithHandednessOnMirroredUvs) {
  GltfBuilder b;
  b.push("images", {{"uri", "normal.png"}});
  b.push("textures", {{"source", 0}});
  const int mat = b.push("materials", {{"normalTexture", {{"index", 0}}}});
  // Quad facing +Z. Regular UVs: u grows along +X, v grows along -Y (glTF's v points down).
  const int pos = b.vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  const int uv = b.vec2({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
  const int uvMirrored = b.vec2({{1, 1}, {0, 1}, {0, 0}, {1, 0}});  // u grows along -X
  const int idx = b.indices16({0, 1, 2, 0, 2, 3});
  const int regular = b.mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}},
                              {"indices", idx},
                              {"material", mat}});
  const int mirrored = b.mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uvMirrored}}},
                               {"indices", idx},
                               {"material", mat}});
  const int plain =
      b.mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}, {"indices", idx}});
  b.scene({b.node({{"mesh", regular}}), b.node({{"mesh", mirrored}}), b.node({{"mesh", plain}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();

  const Primitive& r = scene->meshes[0].primitives[0];
  expectOrthonormalFrames(r);
  for (const glm::vec4& t : r.tangents) {
    expectNear(glm::vec3(t), {1, 0, 0});
    EXPECT_EQ(t.w, 1.0f);
  }
  const Primitive& m = scene->meshes[1].primitives[0];
  expectOrthonormalFrames(m);
  for (size_t v = 0; v < m.tangents.size(); ++v) {
    expectNear(glm::vec3(m.tangents[v]), {-1, 0, 0});
    EXPECT_EQ(m.tangents[v].w, -1.0f);
    // bitangent = w * cross(n, t) points up the image (toward decreasing v): +Y in both.
    const glm::vec3 bitangent =
        m.tangents[v].w * glm::cross(m.normals[v], glm::vec3(m.tangents[v]));
    expectNear(bitangent, {0, 1, 0});
  }
  for (size_t v = 0; v < r.tangents.size(); ++v) {
    const glm::vec3 bitangent =
        r.tangents[v].w * glm::cross(r.normals[v], glm::vec3(r.tangents[v]));
    expectNear(bitangent, {0, 1, 0});
  }
  // Without a normal map no tangents are generated.
  EXPECT_TRUE(scene->meshes[2].primitives[0].tangents.empty());
}

TEST(SceneGltf, TangentsSplitVerticesOnASharedMirrorSeam) {
  GltfBuilder b;
  b.push("images", {{"uri", "normal.png"}});
  b.push("textures", {{"source", 0}});
  b.push("materials", {{"normalTexture", {{"index", 0}, {"texCoord", 1}}}});
  // Two quads sharing the seam x = 1; UV set 1 is mirrored about the seam (u = 1 - |x - 1|).
  const int pos = b.vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}});
  const int uv0 = b.vec2(std::vector<glm::vec2>(6, glm::vec2(0.0f)));
  const int uv1 = b.vec2({{0, 1}, {1, 1}, {1, 0}, {0, 0}, {0, 1}, {0, 0}});
  const int idx = b.indices16({0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2});
  const int m =
      b.mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv1}}},
              {"indices", idx},
              {"material", 0}});
  b.scene({b.node({{"mesh", m}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const Primitive& p = scene->meshes[0].primitives[0];
  EXPECT_EQ(p.positions.size(), 8u);  // the two seam vertices were split
  expectOrthonormalFrames(p);
  for (size_t t = 0; t < p.indices.size(); t += 3) {
    const bool rightQuad = t >= 6;
    for (int k = 0; k < 3; ++k) {
      const glm::vec4& tan = p.tangents[p.indices[t + static_cast<size_t>(k)]];
      EXPECT_EQ(tan.w, rightQuad ? -1.0f : 1.0f);
      expectNear(glm::vec3(tan), rightQuad ? glm::vec3(-1, 0, 0) : glm::vec3(1, 0, 0));
    }
  }
}

TEST(SceneGltf, TwoUvSetsAndNormalizedVertexColors) {
  GltfBuilder b;
  const int pos = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int uv0 = b.vec2({{0.25f, 0.5f}, {1, 0}, {0, 1}});
  const std::vector<uint8_t> uv1Bytes = {0, 255, 255, 0, 51, 102, 0, 0};  // normalized ubyte VEC2
  const int uv1 = b.accessor(b.view(uv1Bytes.data(), 6, 0), kUByte, 3, "VEC2", true);
  const std::vector<uint16_t> rgba = {65535, 0, 32768, 65535, 0,     65535,
                                      0,     0, 13107, 13107, 13107, 65535};
  const int color = b.accessor(b.view(rgba), kUShort, 3, "VEC4", true);
  const int m =
      b.mesh({{"attributes",
               {{"POSITION", pos}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv1}, {"COLOR_0", color}}}});
  // A second primitive with VEC3 unsigned byte colours: alpha becomes 1.
  const std::vector<uint8_t> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0};
  const int color3 = b.accessor(b.view(rgb.data(), 9), kUByte, 3, "VEC3", true);
  const int m2 = b.mesh({{"attributes", {{"POSITION", pos}, {"COLOR_0", color3}}}});
  b.scene({b.node({{"mesh", m}}), b.node({{"mesh", m2}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const Primitive& p = scene->meshes[0].primitives[0];
  ASSERT_EQ(p.uv0.size(), 3u);
  ASSERT_EQ(p.uv1.size(), 3u);
  EXPECT_FLOAT_EQ(p.uv0[0].x, 0.25f);
  EXPECT_FLOAT_EQ(p.uv1[0].y, 1.0f);
  EXPECT_FLOAT_EQ(p.uv1[2].x, 0.2f);
  EXPECT_FLOAT_EQ(p.uv1[2].y, 0.4f);
  ASSERT_EQ(p.colors.size(), 3u);
  EXPECT_FLOAT_EQ(p.colors[0].r, 1.0f);
  EXPECT_NEAR(p.colors[0].b, 32768.0f / 65535.0f, 1e-6f);
  EXPECT_FLOAT_EQ(p.colors[1].a, 0.0f);
  EXPECT_FLOAT_EQ(p.colors[2].r, 0.2f);
  const Primitive& q = scene->meshes[1].primitives[0];
  ASSERT_EQ(q.colors.size(), 3u);
  EXPECT_EQ(q.colors[1], glm::vec4(0, 1, 0, 1));
}

TEST(SceneGltf, QuantizedAndInterleavedAttributes) {
  GltfBuilder b;
  b.useExtension("KHR_mesh_quantization", true);
  // Interleaved: SHORT position (not normalized) + pad, BYTE normalized normal + pad = 12 bytes.
  struct Vertex {
    int16_t p[3];
    int16_t pad;
    int8_t n[3];
    int8_t pad2;
  };
  static_assert(sizeof(Vertex) == 12);
  const std::vector<Vertex> verts = {{{0, 0, 0}, 0, {0, 0, 127}, 0},
                                     {{100, 0, 0}, 0, {0, 0, 127}, 0},
                                     {{0, -200, 0}, 0, {0, -128, 0}, 0}};
  const int v = b.view(verts, sizeof(Vertex));
  const int pos = b.accessor(v, kShort, 3, "VEC3");
  const int nrm = b.accessor(v, kByte, 3, "VEC3", true, 8);
  const int m = b.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}});
  b.scene({b.node({{"mesh", m}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const Primitive& p = scene->meshes[0].primitives[0];
  expectNear(p.positions[1], {100, 0, 0});
  expectNear(p.positions[2], {0, -200, 0});
  expectNear(p.normals[0], {0, 0, 1});
  expectNear(p.normals[2], {0, -1, 0});  // -128 clamps to -1
}

TEST(SceneGltf, SparseAccessorsReplaceValues) {
  GltfBuilder b;
  const std::vector<float> base = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const int baseView = b.view(base);
  const std::vector<uint8_t> sparseIdx = {1, 0, 0, 0};
  const std::vector<float> sparseVal = {5, 6, 7};
  const int iv = b.view(sparseIdx.data(), 1);
  const int vv = b.view(sparseVal);
  json sparse = {{"count", 1},
                 {"indices", {{"bufferView", iv}, {"componentType", kUByte}}},
                 {"values", {{"bufferView", vv}}}};
  const int withView = b.accessor(baseView, kFloat, 3, "VEC3");
  b.doc["accessors"][static_cast<size_t>(withView)]["sparse"] = sparse;
  const int zeros = b.accessor(-1, kFloat, 3, "VEC3");
  b.doc["accessors"][static_cast<size_t>(zeros)]["sparse"] = sparse;
  const int m1 = b.mesh({{"attributes", {{"POSITION", withView}}}});
  const int m2 = b.mesh({{"attributes", {{"POSITION", zeros}}}});
  b.scene({b.node({{"mesh", m1}}), b.node({{"mesh", m2}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const Primitive& p = scene->meshes[0].primitives[0];
  expectNear(p.positions[0], {0, 0, 0});
  expectNear(p.positions[1], {5, 6, 7});
  expectNear(p.positions[2], {0, 1, 0});
  const Primitive& z = scene->meshes[1].primitives[0];
  expectNear(z.positions[0], {0, 0, 0});
  expectNear(z.positions[1], {5, 6, 7});
}

TEST(SceneGltf, NanPositionsDropTheirTrianglesWithAWarning) {
  GltfBuilder b;
  const float nan = std::nanf("");
  const std::vector<float> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0, nan, 0, 0};
  const int a = b.accessor(b.view(pos), kFloat, 4, "VEC3");
  const int idx = b.indices16({0, 1, 2, 1, 3, 2, 0, 0, 1});  // the last one is degenerate: kept
  const int m = b.mesh({{"attributes", {{"POSITION", a}}}, {"indices", idx}});
  b.scene({b.node({{"mesh", m}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const Primitive& p = scene->meshes[0].primitives[0];
  EXPECT_EQ(p.indices, (std::vector<uint32_t>{0, 1, 2, 0, 0, 1}));
  EXPECT_TRUE(hasWarning(*scene, "non-finite"));
  EXPECT_TRUE(std::isfinite(scene->bounds.radius()));
  for (const glm::vec3& n : p.normals) EXPECT_TRUE(std::isfinite(n.x + n.y + n.z));
}

TEST(SceneGltf, EmptySceneIsAllowedWithAWarning) {
  GltfBuilder b;
  b.scene({b.node({{"name", "empty"}})});
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  EXPECT_TRUE(scene->meshes.empty());
  EXPECT_TRUE(hasWarning(*scene, "no meshes"));
  auto bare = loadText(R"({"asset":{"version":"2.0"}})");
  ASSERT_TRUE(bare.ok()) << bare.message();
  EXPECT_EQ(bare->triangleCount(), 0u);
}

}  // namespace
}  // namespace penumbra::test
