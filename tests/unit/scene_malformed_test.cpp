// Malformed glTF input: every case is a one-line error naming the file (or, for textures, a
// warning), never a crash, hang or exception.
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "scene_gltf_builder.h"

namespace penumbra::test {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

GltfBuilder texturedTriangle() {
  GltfBuilder b;
  const int pos = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int nrm = b.vec3({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
  const int uv = b.vec2({{0, 0}, {1, 0}, {0, 1}});
  const int idx = b.indices16({0, 1, 2});
  b.push("images", {{"uri", "data:image/png;base64,AAAA"}});
  b.push("textures", {{"source", 0}});
  b.push("materials", {{"normalTexture", {{"index", 0}}}});
  const int m = b.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}},
                        {"indices", idx},
                        {"material", 0}});
  b.scene({b.node({{"mesh", m}})});
  return b;
}

void expectError(const Result<Scene>& scene, const std::string& name, const std::string& needle) {
  ASSERT_FALSE(scene.ok()) << "expected an error containing '" << needle << "'";
  EXPECT_THAT(scene.message(), StartsWith(name + ": "));
  EXPECT_THAT(scene.message(), HasSubstr(needle));
  EXPECT_EQ(scene.message().find('\n'), std::string::npos) << "not one line: " << scene.message();
}

Result<Scene> loadBytes(const std::vector<uint8_t>& bytes, const std::string& name,
                        const LoadOptions& options = {}) {
  return loadGltfFromMemory(bytes, "", name, options);
}

TEST(SceneGltfMalformed, EveryTruncationOfAGlbIsAnError) {
  const auto glb = texturedTriangle().glb();
  ASSERT_TRUE(loadBytes(glb, "t.glb").ok());
  for (size_t n = 0; n < glb.size(); ++n) {
    const std::vector<uint8_t> cut(glb.begin(), glb.begin() + static_cast<std::ptrdiff_t>(n));
    auto scene = loadBytes(cut, "t.glb");
    ASSERT_FALSE(scene.ok()) << "prefix of " << n << " bytes loaded";
    EXPECT_THAT(scene.message(), StartsWith("t.glb: "));
    if (n >= 12) {
      EXPECT_THAT(scene.message(), HasSubstr("truncated"));
    }
  }
}

TEST(SceneGltfMalformed, WrongMagic) {
  auto glb = texturedTriangle().glb();
  glb[3] = 'X';
  expectError(loadBytes(glb, "model.glb"), "model.glb", "wrong magic");
  // Named .gltf, the same bytes are not JSON either.
  expectError(loadBytes(glb, "model.gltf"), "model.gltf", "bad JSON");
  auto glb2 = texturedTriangle().glb();
  glb2[4] = 1;  // container version 1
  expectError(loadBytes(glb2, "v1.glb"), "v1.glb", "version 1");
}

TEST(SceneGltfMalformed, BadJson) {
  expectError(loadText(R"({"asset": {"version": "2.0"}, "nodes": [)", "bad.gltf"), "bad.gltf",
              "bad JSON");
  expectError(loadText("[1, 2, 3]", "arr.gltf"), "arr.gltf", "not an object");
  expectError(loadText(R"({"nodes": []})", "noasset.gltf"), "noasset.gltf", "asset");
  expectError(loadText(R"({"asset": {"version": "2.0"}, "nodes": 5})", "t.gltf"), "t.gltf",
              "nodes: must be an array");
  expectError(loadText(R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": "zero"}]})", "t.gltf"),
              "t.gltf", "nodes[0].mesh");
  expectError(loadText(R"({"asset": {"version": "1.0"}})", "old.gltf"), "old.gltf", "version");
  expectError(loadText("", "empty.gltf"), "empty.gltf", "empty");
}

TEST(SceneGltfMalformed, AccessorOutOfRangeOfItsBufferView) {
  GltfBuilder b = texturedTriangle();
  b.doc["accessors"][0]["count"] = 10;
  expectError(b.load(), "test.gltf", "accessor 0 (mesh 0 primitive 0 POSITION) is out of range");
  GltfBuilder c = texturedTriangle();
  c.doc["accessors"][1]["byteOffset"] = uint64_t{1} << 62;  // overflow bait
  expectError(c.load(), "test.gltf", "accessor 1");
  GltfBuilder d = texturedTriangle();
  d.doc["bufferViews"][0]["byteStride"] = 4;  // smaller than a VEC3 of floats
  expectError(d.load(), "test.gltf", "byteStride");
}

TEST(SceneGltfMalformed, BufferViewOutOfRangeOfItsBuffer) {
  GltfBuilder b = texturedTriangle();
  b.doc["bufferViews"][1]["byteLength"] = 100000;
  expectError(b.load(), "test.gltf", "bufferView 1 (offset");
  expectError(b.load(true), "test.glb", "out of range of buffer 0");
}

TEST(SceneGltfMalformed, IndexReferencesOutOfRange) {
  GltfBuilder b = texturedTriangle();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99;
  expectError(b.load(), "test.gltf",
              "meshes[0].primitives[0].attributes.POSITION: index 99 is out of range");
  GltfBuilder c = texturedTriangle();
  c.doc["scenes"][0]["nodes"] = {3};
  expectError(c.load(), "test.gltf", "scenes[0].nodes[0]");
  GltfBuilder d = texturedTriangle();
  d.doc["materials"][0]["normalTexture"]["index"] = -1;
  expectError(d.load(), "test.gltf", "materials[0].normalTexture.index");
}

TEST(SceneGltfMalformed, NumbersBeyondFloatRangeAreErrorsByPath) {
  // JSON holds 1e39; a float cannot (it would become infinity inside the renderer).
  GltfBuilder b = texturedTriangle();
  b.doc["materials"][0]["pbrMetallicRoughness"] = {{"baseColorFactor", {1.0, 1e39, 1.0, 1.0}}};
  expectError(b.load(), "test.gltf",
              "materials[0].pbrMetallicRoughness.baseColorFactor: must contain only finite "
              "numbers within float range");
  GltfBuilder c = texturedTriangle();
  c.doc["materials"][0]["pbrMetallicRoughness"] = {{"roughnessFactor", -1e39}};
  expectError(c.load(), "test.gltf",
              "materials[0].pbrMetallicRoughness.roughnessFactor: must be a finite number");
  GltfBuilder d = texturedTriangle();
  d.doc["nodes"][0]["translation"] = {0.0, 3.5e38, 0.0};
  expectError(d.load(), "test.gltf", "nodes[0].translation");
  // The largest float itself is still a number (what it does to the scene is another matter).
  GltfBuilder e = texturedTriangle();
  e.doc["materials"][0]["emissiveFactor"] = {0.0, 0.0, 3.4e38};
  EXPECT_TRUE(e.load().ok()) << e.load().message();
}

TEST(SceneGltfMalformed, VertexIndexOutOfRange) {
  GltfBuilder b;
  const int pos = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int idx = b.indices16({0, 1, 5});
  b.scene({b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}})});
  expectError(b.load(), "test.gltf",
              "index 5 (at position 2) is out of range of the vertex count 3");
}

TEST(SceneGltfMalformed, MissingPositionAndMismatchedCounts) {
  GltfBuilder b = texturedTriangle();
  b.doc["meshes"][0]["primitives"][0]["attributes"].erase("POSITION");
  expectError(b.load(), "test.gltf", "no POSITION");
  GltfBuilder c = texturedTriangle();
  c.doc["accessors"][1]["count"] = 2;
  expectError(c.load(), "test.gltf", "NORMAL has 2 elements but POSITION has 3");
}

TEST(SceneGltfMalformed, MissingBufferFileIsAnError) {
  GltfBuilder b = texturedTriangle();
  b.autoBuffer = false;
  b.doc["buffers"] = json::array({{{"byteLength", b.bin.size()}, {"uri", "missing.bin"}}});
  expectError(b.load(), "test.gltf", "buffer 0: cannot open");
  expectError(b.load(), "test.gltf", "missing.bin");
  auto viaPath = loadGltf("/nonexistent/dir/scene.gltf");
  expectError(viaPath, "/nonexistent/dir/scene.gltf", "no such file");
}

TEST(SceneGltfMalformed, MissingTextureIsOnlyAWarning) {
  GltfBuilder b = texturedTriangle();
  b.doc["images"][0] = {{"uri", "gone.png"}};
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  ASSERT_EQ(scene->images.size(), 1u);
  EXPECT_TRUE(scene->images[0].placeholder);
  EXPECT_EQ(scene->images[0].pixels, (std::vector<uint8_t>{128, 128, 255, 255}));  // normal map
  EXPECT_TRUE(hasWarning(*scene, "gone.png"));
}

TEST(SceneGltfMalformed, HugeDeclaredPngSaysHowLarge) {
  // A PNG header declaring 60000 x 60000: stb_image calls that an "unknown image type"; the
  // warning must say what is wrong.
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n', 0, 0, 0, 13, 'I', 'H',
                              'D', 'R', 0, 0, 0xEA, 0x60, 0, 0, 0xEA, 0x60, 8, 6, 0, 0,
                              0,           // depth, colour type, compression, filter,
                                           // interlace
                              0, 0, 0, 0,  // CRC (not checked)
                              0, 0, 0, 0, 'I', 'E', 'N', 'D', 0, 0, 0, 0};
  GltfBuilder b = texturedTriangle();
  b.doc["images"][0] = {{"uri", "data:image/png;base64," + base64(png)}};
  b.doc["materials"][0] = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}};
  auto scene = b.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  EXPECT_TRUE(scene->images[0].placeholder);
  EXPECT_TRUE(hasWarning(*scene, "60000x60000 PNG is too large to decode"))
      << (scene->warnings.empty() ? std::string("no warnings") : scene->warnings.back());
}

TEST(SceneGltfMalformed, CyclicOrSharedNodesAreErrors) {
  GltfBuilder b = texturedTriangle();  // node 0 holds the mesh
  b.node({{"children", {2}}});         // node 1 -> 2
  b.node({{"children", {1}}});         // node 2 -> 1: a cycle outside the scene
  expectError(b.load(), "test.gltf", "cycle");

  GltfBuilder c = texturedTriangle();
  c.doc["nodes"][0]["children"] = {0};
  expectError(c.load(), "test.gltf", "node 0 lists itself as a child");

  GltfBuilder d = texturedTriangle();
  d.node({{"children", {0}}});
  d.node({{"children", {0}}});
  expectError(d.load(), "test.gltf", "node 0 has more than one parent");

  GltfBuilder e = texturedTriangle();
  e.node({{"children", {0}}});
  e.doc["scenes"][0]["nodes"] = {1, 0};  // node 0 as a root and as a child
  expectError(e.load(), "test.gltf", "reached twice");

  // A long chain is fine and does not recurse.
  GltfBuilder f = texturedTriangle();
  int prev = 0;
  for (int i = 0; i < 20000; ++i) prev = f.node({{"children", {prev}}});
  f.doc["scenes"][0]["nodes"] = {prev};
  auto deep = f.load();
  ASSERT_TRUE(deep.ok()) << deep.message();
  EXPECT_EQ(deep->instances.size(), 1u);
}

TEST(SceneGltfMalformed, GiganticDeclaredSizesAreErrorsNotCrashes) {
  GltfBuilder b = texturedTriangle();
  b.autoBuffer = false;
  b.doc["buffers"] = json::array(
      {{{"byteLength", uint64_t{5} << 30}, {"uri", "data:application/octet-stream;base64,AAAA"}}});
  expectError(b.load(), "test.gltf", "memory budget");

  GltfBuilder glb = texturedTriangle();
  glb.autoBuffer = false;
  glb.doc["buffers"] = json::array({{{"byteLength", uint64_t{1} << 40}}});
  expectError(glb.load(true), "test.glb", "declares 1099511627776 bytes");

  GltfBuilder c = texturedTriangle();
  c.doc["accessors"].push_back(
      {{"componentType", kFloat}, {"count", 4000000000u}, {"type", "VEC3"}});
  c.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = 4;
  c.doc["accessors"][4]["type"] = "VEC2";
  expectError(c.load(), "test.gltf", "memory budget");

  GltfBuilder d = texturedTriangle();
  d.doc["accessors"][0]["count"] = uint64_t{1} << 50;
  expectError(d.load(), "test.gltf", "absurd count");

  GltfBuilder e = texturedTriangle();
  e.doc["accessors"][0]["count"] = -1;
  expectError(e.load(), "test.gltf", "accessors[0].count");
}

TEST(SceneGltfMalformed, GlbBinChunkShorterThanBuffer) {
  GltfBuilder b = texturedTriangle();
  b.autoBuffer = false;
  b.doc["buffers"] = json::array({{{"byteLength", b.bin.size() + 64}}});
  expectError(b.load(true), "test.glb", "BIN chunk");
}

TEST(SceneGltfMalformed, SparseIndexOutOfRange) {
  GltfBuilder b = texturedTriangle();
  const std::vector<uint8_t> idx = {7, 0, 0, 0};
  const std::vector<float> val = {1, 2, 3};
  const int iv = b.view(idx.data(), 1);
  const int vv = b.view(val);
  b.doc["accessors"][0]["sparse"] = {{"count", 1},
                                     {"indices", {{"bufferView", iv}, {"componentType", kUByte}}},
                                     {"values", {{"bufferView", vv}}}};
  expectError(b.load(), "test.gltf", "sparse index 7 is out of range");
}

TEST(SceneGltfMalformed, MalformedDataUri) {
  GltfBuilder b = texturedTriangle();
  b.autoBuffer = false;
  b.doc["buffers"] =
      json::array({{{"byteLength", 4}, {"uri", "data:application/octet-stream;base64,@@@@"}}});
  expectError(b.load(), "test.gltf", "base64");
}

// Random byte corruption of a complete .glb: every result is a clean error or a scene.
TEST(SceneGltfMalformed, RandomCorruptionNeverCrashes) {
  GltfBuilder b = texturedTriangle();
  b.push("cameras", {{"type", "perspective"}, {"perspective", {{"yfov", 1}, {"znear", 0.1}}}});
  b.doc["nodes"][0]["camera"] = 0;
  const auto glb = b.glb();
  std::mt19937 rng(1234);
  int errors = 0;
  for (int iteration = 0; iteration < 2000; ++iteration) {
    auto bytes = glb;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f) {
      bytes[rng() % bytes.size()] = static_cast<uint8_t>(rng());
    }
    auto scene = loadBytes(bytes, "fuzz.glb");
    if (!scene.ok()) {
      ++errors;
      EXPECT_THAT(scene.message(), StartsWith("fuzz.glb: "));
    }
  }
  EXPECT_GT(errors, 0);
}

}  // namespace
}  // namespace penumbra::test
