// Capture stand-ins (scene/mesh_lod.h): dense meshes get a much smaller triangle list that
// stays within the error bound of the original surface; small meshes keep their own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "scene/mesh_lod.h"

namespace penumbra {
namespace {

// A bumpy sphere of radius about 1 as a (rings x segments) latitude-longitude grid.
Primitive bumpySphere(int rings, int segments) {
  Primitive p;
  for (int r = 0; r <= rings; ++r) {
    const float theta = 3.14159265f * static_cast<float>(r) / static_cast<float>(rings);
    for (int s = 0; s <= segments; ++s) {
      const float phi = 6.28318531f * static_cast<float>(s) / static_cast<float>(segments);
      const glm::vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
      const float bump = 1.0f + 0.05f * std::sin(5.0f * phi) * std::sin(4.0f * theta);
      p.positions.push_back(d * bump);
      p.bounds.extend(d * bump);
    }
  }
  const auto at = [&](int r, int s) { return static_cast<uint32_t>(r * (segments + 1) + s); };
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      p.indices.insert(p.indices.end(), {at(r, s), at(r + 1, s), at(r + 1, s + 1)});
      p.indices.insert(p.indices.end(), {at(r, s), at(r + 1, s + 1), at(r, s + 1)});
    }
  }
  return p;
}

// Distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5).
float pointTriangleDistance(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return glm::length(p - a);
  const glm::vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return glm::length(p - b);
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
  const glm::vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return glm::length(p - c);
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  }
  const float denom = 1.0f / (va + vb + vc);
  return glm::length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

float distanceToMesh(glm::vec3 p, const std::vector<glm::vec3>& pos,
                     const std::vector<uint32_t>& idx) {
  float best = INFINITY;
  for (size_t i = 0; i + 2 < idx.size(); i += 3) {
    best = std::min(best, pointTriangleDistance(p, pos[idx[i]], pos[idx[i + 1]], pos[idx[i + 2]]));
  }
  return best;
}

TEST(MeshLodTest, DenseMeshGetsAFarSmallerStandInWithinTheErrorBound) {
  const Primitive sphere = bumpySphere(128, 128);  // 32,768 triangles
  const float diagonal = 20.0f;                    // the sphere in a room 20 units across
  const std::vector<uint32_t> lod = captureLod(sphere, 1.0f, diagonal);
  ASSERT_FALSE(lod.empty());
  ASSERT_EQ(lod.size() % 3, 0u);
  EXPECT_LT(lod.size() * 8, sphere.indices.size()) << "at least 8x fewer triangles";
  for (uint32_t i : lod) ASSERT_LT(i, sphere.positions.size());
  // Every 7th original vertex lies near the stand-in's surface. meshoptimizer's error metric
  // is quadric (a distance estimate), so allow twice the bound.
  const float bound = kCaptureLodErrorFraction * diagonal;
  float worst = 0.0f;
  for (size_t v = 0; v < sphere.positions.size(); v += 7) {
    worst = std::max(worst, distanceToMesh(sphere.positions[v], sphere.positions, lod));
  }
  EXPECT_LT(worst, 2.0f * bound) << "bound " << bound;
  EXPECT_GT(worst, 0.0f) << "the stand-in is not the mesh itself";
}

TEST(MeshLodTest, TheBoundIsInWorldUnits) {
  const Primitive sphere = bumpySphere(128, 128);
  const std::vector<uint32_t> room = captureLod(sphere, 1.0f, 20.0f);
  // The same mesh drawn 10x larger (or in a scene 10x smaller) must keep more of its detail.
  const std::vector<uint32_t> scaled = captureLod(sphere, 10.0f, 20.0f);
  const std::vector<uint32_t> small = captureLod(sphere, 1.0f, 2.0f);
  ASSERT_FALSE(room.empty());
  ASSERT_FALSE(scaled.empty());
  EXPECT_GT(scaled.size(), room.size() * 2);
  EXPECT_EQ(scaled.size(), small.size()) << "only the ratio of scale to diagonal matters";
}

TEST(MeshLodTest, SmallOrDegenerateMeshesKeepTheirOwnTriangles) {
  const Primitive small = bumpySphere(16, 16);  // 512 triangles
  EXPECT_TRUE(captureLod(small, 1.0f, 20.0f).empty());
  const Primitive sphere = bumpySphere(128, 128);
  EXPECT_TRUE(captureLod(sphere, 0.0f, 20.0f).empty());
  EXPECT_TRUE(captureLod(sphere, 1.0f, 0.0f).empty());
  EXPECT_TRUE(captureLod(sphere, 1.0f, NAN).empty());
  Primitive flat = sphere;
  flat.bounds = Bounds{};  // no extent known
  EXPECT_TRUE(captureLod(flat, 1.0f, 20.0f).empty());
  // A NaN vertex the loader left unreferenced (it drops the triangles on it).
  Primitive poisoned = sphere;
  poisoned.positions.push_back(glm::vec3(NAN, 0.0f, 0.0f));
  EXPECT_TRUE(captureLod(poisoned, 1.0f, 20.0f).empty());
}

}  // namespace
}  // namespace penumbra
