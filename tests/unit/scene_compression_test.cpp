// Compressed geometry: KHR_draco_mesh_compression (encoded here with Draco's encoder) and
// EXT_meshopt_compression (encoded with meshoptimizer, including the octahedral filter).
#include <algorithm>
#include <array>
#include <cmath>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include "scene_gltf_builder.h"

namespace penumbra::test {
namespace {

using ::testing::HasSubstr;

// A 4x4-vertex grid over [0,1]^2 at z = 0: 9 quads, 18 counter-clockwise triangles.
struct Grid {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;
};

Grid makeGrid() {
  Grid g;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      const glm::vec3 p(static_cast<float>(x) / 3.0f, static_cast<float>(y) / 3.0f, 0.0f);
      g.positions.push_back(p);
      g.normals.push_back(glm::normalize(glm::vec3(p.x - 0.5f, p.y - 0.5f, 1.0f)));
      g.uvs.emplace_back(p.x, 1.0f - p.y);
    }
  }
  for (uint32_t y = 0; y < 3; ++y) {
    for (uint32_t x = 0; x < 3; ++x) {
      const uint32_t i = y * 4 + x;
      g.indices.insert(g.indices.end(), {i, i + 1, i + 5, i, i + 5, i + 4});
    }
  }
  return g;
}

// Checks a loaded primitive against the grid: the same surface, the same winding.
void expectGridSurface(const Primitive& p, float tolerance) {
  ASSERT_EQ(p.indices.size(), 54u);
  float area = 0.0f;
  for (size_t t = 0; t < p.indices.size(); t += 3) {
    const glm::vec3 n = glm::cross(p.positions[p.indices[t + 1]] - p.positions[p.indices[t]],
                                   p.positions[p.indices[t + 2]] - p.positions[p.indices[t]]);
    EXPECT_GT(n.z, 0.0f) << "triangle " << t / 3 << " flipped";
    area += 0.5f * glm::length(n);
  }
  EXPECT_NEAR(area, 1.0f, 10 * tolerance);
  for (const glm::vec3& v : p.positions) {
    EXPECT_NEAR(v.x * 3.0f, std::round(v.x * 3.0f), 3 * tolerance);
    EXPECT_NEAR(v.y * 3.0f, std::round(v.y * 3.0f), 3 * tolerance);
    EXPECT_NEAR(v.z, 0.0f, tolerance);
  }
  EXPECT_NEAR(p.bounds.max.x, 1.0f, tolerance);
  EXPECT_NEAR(p.bounds.max.y, 1.0f, tolerance);
}

struct DracoFile {
  GltfBuilder builder;
  uint32_t positionId = 0, normalId = 0, uvId = 0;
  uint32_t jointsId = 0, weightsId = 0;
};

// The grid, Draco-compressed; `skinWeight` >= 0 adds JOINTS_0 (every vertex on joint 0) and
// WEIGHTS_0 (that weight on it) inside the compressed data, and a skin whose one joint sits at
// (0, 0, 3), as the Khronos CesiumMan's Draco variant carries its skin.
DracoFile dracoGrid(float skinWeight = -1.0f) {
  const Grid g = makeGrid();
  const int faces = static_cast<int>(g.indices.size() / 3);
  draco::TriangleSoupMeshBuilder mb;
  mb.Start(faces);
  const int pos = mb.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int nrm = mb.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  const int uv = mb.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  const bool skinned = skinWeight >= 0.0f;
  const int jnt =
      skinned ? mb.AddAttribute(draco::GeometryAttribute::GENERIC, 4, draco::DT_UINT8) : -1;
  const int wgt =
      skinned ? mb.AddAttribute(draco::GeometryAttribute::GENERIC, 4, draco::DT_FLOAT32) : -1;
  const uint8_t joint[4] = {0, 0, 0, 0};
  const float weight[4] = {skinWeight, 0.0f, 0.0f, 0.0f};
  for (int f = 0; f < faces; ++f) {
    if (skinned) {
      mb.SetAttributeValuesForFace(jnt, draco::FaceIndex(f), joint, joint, joint);
      mb.SetAttributeValuesForFace(wgt, draco::FaceIndex(f), weight, weight, weight);
    }
    const uint32_t* i = &g.indices[static_cast<size_t>(f) * 3];
    mb.SetAttributeValuesForFace(pos, draco::FaceIndex(f), &g.positions[i[0]], &g.positions[i[1]],
                                 &g.positions[i[2]]);
    mb.SetAttributeValuesForFace(nrm, draco::FaceIndex(f), &g.normals[i[0]], &g.normals[i[1]],
                                 &g.normals[i[2]]);
    mb.SetAttributeValuesForFace(uv, draco::FaceIndex(f), &g.uvs[i[0]], &g.uvs[i[1]], &g.uvs[i[2]]);
  }
  std::unique_ptr<draco::Mesh> mesh = mb.Finalize();
  EXPECT_TRUE(mesh);
  DracoFile out;
  out.positionId = mesh->attribute(pos)->unique_id();
  out.normalId = mesh->attribute(nrm)->unique_id();
  out.uvId = mesh->attribute(uv)->unique_id();
  if (skinned) {
    out.jointsId = mesh->attribute(jnt)->unique_id();
    out.weightsId = mesh->attribute(wgt)->unique_id();
  }

  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
  draco::EncoderBuffer encoded;
  const draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &encoded);
  EXPECT_TRUE(status.ok()) << status.error_msg_string();

  // The accessor counts are those of the decoded mesh (Draco may reorder and split points).
  draco::DecoderBuffer db;
  db.Init(encoded.data(), encoded.size());
  auto decoded = draco::Decoder().DecodeMeshFromBuffer(&db);
  EXPECT_TRUE(decoded.ok());
  const size_t points = decoded.ok() ? decoded.value()->num_points() : 0;

  GltfBuilder& b = out.builder;
  b.useExtension("KHR_draco_mesh_compression", true);
  const int view = b.view(encoded.data(), encoded.size());
  const int aPos = b.accessor(-1, kFloat, points, "VEC3");
  const int aNrm = b.accessor(-1, kFloat, points, "VEC3");
  const int aUv = b.accessor(-1, kFloat, points, "VEC2");
  const int aIdx = b.accessor(-1, kUShort, g.indices.size(), "SCALAR");
  const int m = b.mesh({{"attributes", {{"POSITION", aPos}, {"NORMAL", aNrm}, {"TEXCOORD_0", aUv}}},
                        {"indices", aIdx},
                        {"extensions",
                         {{"KHR_draco_mesh_compression",
                           {{"bufferView", view},
                            {"attributes",
                             {{"POSITION", out.positionId},
                              {"NORMAL", out.normalId},
                              {"TEXCOORD_0", out.uvId}}}}}}}});
  if (!skinned) {
    b.scene({b.node({{"mesh", m}})});
    return out;
  }
  json& prim = b.doc["meshes"][static_cast<size_t>(m)]["primitives"][0];
  prim["attributes"]["JOINTS_0"] = b.accessor(-1, kUByte, points, "VEC4");
  prim["attributes"]["WEIGHTS_0"] = b.accessor(-1, kFloat, points, "VEC4");
  prim["extensions"]["KHR_draco_mesh_compression"]["attributes"]["JOINTS_0"] = out.jointsId;
  prim["extensions"]["KHR_draco_mesh_compression"]["attributes"]["WEIGHTS_0"] = out.weightsId;
  const int joint0 = b.node({{"name", "joint"}, {"translation", {0, 0, 3}}});
  b.push("skins", {{"joints", {joint0}}});
  b.scene({joint0, b.node({{"mesh", m}, {"skin", 0}})});
  return out;
}

bool warnsDrawsNothing(const Scene& scene) {
  return std::ranges::any_of(scene.warnings, [](const std::string& w) {
    return w.find("draws nothing") != std::string::npos;
  });
}

TEST(SceneGltfCompression, DracoCompressedMeshDecodes) {
  DracoFile file = dracoGrid();
  for (bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "glb" : "gltf");
    auto scene = file.builder.load(binary);
    ASSERT_TRUE(scene.ok()) << scene.message();
    const Primitive& p = scene->meshes.at(0).primitives.at(0);
    expectGridSurface(p, 1e-3f);
    ASSERT_EQ(p.normals.size(), p.positions.size());
    ASSERT_EQ(p.uv0.size(), p.positions.size());
    for (size_t v = 0; v < p.positions.size(); ++v) {
      const glm::vec3 expected =
          glm::normalize(glm::vec3(p.positions[v].x - 0.5f, p.positions[v].y - 0.5f, 1.0f));
      EXPECT_GT(glm::dot(p.normals[v], expected), 0.999f);
      EXPECT_NEAR(p.uv0[v].x, p.positions[v].x, 2e-3f);
      EXPECT_NEAR(p.uv0[v].y, 1.0f - p.positions[v].y, 2e-3f);
    }
  }
}

// The skin's JOINTS_0 and WEIGHTS_0 live in the compressed data; read from their (empty)
// accessors they were zeros and collapsed the mesh to a point: an empty picture, no word.
TEST(SceneGltfCompression, DracoCompressedSkinPosesTheMesh) {
  DracoFile file = dracoGrid(1.0f);
  auto scene = file.builder.load();
  ASSERT_TRUE(scene.ok()) << scene.message();
  const Primitive& p = scene->meshes.at(0).primitives.at(0);
  float area = 0.0f;
  for (size_t t = 0; t < p.indices.size(); t += 3) {
    area +=
        0.5f * glm::length(glm::cross(p.positions[p.indices[t + 1]] - p.positions[p.indices[t]],
                                      p.positions[p.indices[t + 2]] - p.positions[p.indices[t]]));
  }
  EXPECT_NEAR(area, 1.0f, 1e-2f);
  for (const glm::vec3& v : p.positions) EXPECT_NEAR(v.z, 3.0f, 1e-3f);  // on the joint
  EXPECT_FALSE(warnsDrawsNothing(*scene));

  // Weights of zero (an invalid skin) still collapse it: now with a warning that says so.
  auto collapsed = dracoGrid(0.0f).builder.load();
  ASSERT_TRUE(collapsed.ok()) << collapsed.message();
  EXPECT_TRUE(warnsDrawsNothing(*collapsed));
}

TEST(SceneGltfCompression, BrokenDracoDataIsAnError) {
  DracoFile file = dracoGrid();
  GltfBuilder corrupt = file.builder;
  std::fill(corrupt.bin.begin(), corrupt.bin.end(), uint8_t{0x5A});
  auto scene = corrupt.load();
  ASSERT_FALSE(scene.ok());
  EXPECT_THAT(scene.message(), HasSubstr("Draco decoding failed"));

  GltfBuilder wrongId = file.builder;
  wrongId.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]
             ["attributes"]["NORMAL"] = 99;
  auto scene2 = wrongId.load();
  ASSERT_FALSE(scene2.ok());
  EXPECT_THAT(scene2.message(), HasSubstr("Draco attribute id 99"));
}

struct MeshoptFile {
  GltfBuilder builder;
  size_t positionsOffset = 0;
  Grid grid;
};

MeshoptFile meshoptGrid() {
  MeshoptFile out;
  const Grid& g = out.grid = makeGrid();
  const size_t n = g.positions.size();
  GltfBuilder& b = out.builder;
  b.useExtension("EXT_meshopt_compression", true);
  b.useExtension("KHR_mesh_quantization", true);

  std::vector<uint8_t> pos(meshopt_encodeVertexBufferBound(n, 12));
  pos.resize(meshopt_encodeVertexBuffer(pos.data(), pos.size(), g.positions.data(), n, 12));
  // Normals: 8-bit octahedral (xyzw int8 per vertex), as gltfpack writes them.
  std::vector<float> n4;
  for (const auto& v : g.normals) n4.insert(n4.end(), {v.x, v.y, v.z, 0.0f});
  std::vector<int8_t> oct(n * 4);
  meshopt_encodeFilterOct(oct.data(), n, 4, 8, n4.data());
  std::vector<uint8_t> nrm(meshopt_encodeVertexBufferBound(n, 4));
  nrm.resize(meshopt_encodeVertexBuffer(nrm.data(), nrm.size(), oct.data(), n, 4));
  std::vector<uint8_t> idx(meshopt_encodeIndexBufferBound(g.indices.size(), n));
  idx.resize(meshopt_encodeIndexBuffer(idx.data(), idx.size(), g.indices.data(), g.indices.size()));

  out.positionsOffset = b.append(pos.data(), pos.size());
  const size_t nrmOffset = b.append(nrm.data(), nrm.size());
  const size_t idxOffset = b.append(idx.data(), idx.size());
  auto compressedView = [&](size_t fallbackOffset, size_t fallbackLength, size_t stride,
                            size_t offset, size_t length, size_t count, const char* mode,
                            const char* filter) {
    json ext = {{"buffer", 0},          {"byteOffset", offset}, {"byteLength", length},
                {"byteStride", stride}, {"count", count},       {"mode", mode}};
    if (filter) ext["filter"] = filter;
    json v = {{"buffer", 1},
              {"byteOffset", fallbackOffset},
              {"byteLength", fallbackLength},
              {"extensions", {{"EXT_meshopt_compression", ext}}}};
    if (std::string(mode) == "ATTRIBUTES") v["byteStride"] = stride;
    return b.push("bufferViews", v);
  };
  const int vPos =
      compressedView(0, n * 12, 12, out.positionsOffset, pos.size(), n, "ATTRIBUTES", nullptr);
  const int vNrm =
      compressedView(n * 12, n * 4, 4, nrmOffset, nrm.size(), n, "ATTRIBUTES", "OCTAHEDRAL");
  const int vIdx = compressedView(n * 16, g.indices.size() * 2, 2, idxOffset, idx.size(),
                                  g.indices.size(), "TRIANGLES", nullptr);
  const int aPos = b.accessor(vPos, kFloat, n, "VEC3");
  const int aNrm = b.accessor(vNrm, kByte, n, "VEC3", true);
  const int aIdx = b.accessor(vIdx, kUShort, g.indices.size(), "SCALAR");
  const int m = b.mesh({{"attributes", {{"POSITION", aPos}, {"NORMAL", aNrm}}}, {"indices", aIdx}});
  b.scene({b.node({{"mesh", m}})});
  b.autoBuffer = false;
  return out;
}

void setMeshoptBuffers(GltfBuilder& b, bool binary, size_t fallbackLength) {
  json buffer0 = {{"byteLength", b.bin.size()}};
  if (!binary) buffer0["uri"] = "data:application/octet-stream;base64," + base64(b.bin);
  json fallback = {{"byteLength", fallbackLength},
                   {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}};
  b.doc["buffers"] = json::array({buffer0, fallback});
}

TEST(SceneGltfCompression, MeshoptCompressedBufferViewsDecode) {
  MeshoptFile file = meshoptGrid();
  const Grid& g = file.grid;
  for (bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "glb" : "gltf");
    setMeshoptBuffers(file.builder, binary, g.positions.size() * 16 + g.indices.size() * 2);
    auto scene = file.builder.load(binary);
    ASSERT_TRUE(scene.ok()) << scene.message();
    const Primitive& p = scene->meshes.at(0).primitives.at(0);
    // The vertex codec is lossless; the index codec keeps every triangle and its winding but
    // may rotate its corners.
    EXPECT_EQ(p.positions, g.positions);
    ASSERT_EQ(p.indices.size(), g.indices.size());
    auto canonical = [](const uint32_t* t) {
      const int first = t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2);
      return std::array<uint32_t, 3>{t[first], t[(first + 1) % 3], t[(first + 2) % 3]};
    };
    for (size_t t = 0; t < g.indices.size(); t += 3) {
      EXPECT_EQ(canonical(&p.indices[t]), canonical(&g.indices[t])) << "triangle " << t / 3;
    }
    expectGridSurface(p, 1e-6f);
    // 8-bit octahedral normals: a few hundredths.
    ASSERT_EQ(p.normals.size(), g.normals.size());
    for (size_t v = 0; v < g.normals.size(); ++v) {
      EXPECT_GT(glm::dot(p.normals[v], g.normals[v]), 0.998f) << "vertex " << v;
    }
  }
}

TEST(SceneGltfCompression, BrokenMeshoptDataIsAnError) {
  MeshoptFile file = meshoptGrid();
  file.builder.bin[file.positionsOffset] = 0;  // the vertex codec's header byte
  setMeshoptBuffers(file.builder, false, 16 * 16 + 54 * 2);
  auto scene = file.builder.load();
  ASSERT_FALSE(scene.ok());
  EXPECT_THAT(scene.message(), HasSubstr("bufferView 0 (EXT_meshopt_compression)"));
  EXPECT_THAT(scene.message(), HasSubstr("malformed"));

  MeshoptFile odd = meshoptGrid();
  odd.builder.doc["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["count"] = 53;
  setMeshoptBuffers(odd.builder, false, 16 * 16 + 54 * 2);
  auto scene2 = odd.builder.load();
  ASSERT_FALSE(scene2.ok());
  EXPECT_THAT(scene2.message(), HasSubstr("not a multiple of 3"));
}

}  // namespace
}  // namespace penumbra::test
