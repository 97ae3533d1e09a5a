// Probe relocation (progressive/probe_relocation.h): a probe inside a solid leaves it through
// its nearest face, one at a wall's nose steps back, one with a clear view stays, and none
// leaves its cell. The sights are traced here against boxes, as a capture would see them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "progressive/probe_relocation.h"

namespace penumbra::progressive {
namespace {

struct Box {
  glm::vec3 lo, hi;
  bool solid;  // faces point out (a block); otherwise in (a room seen from inside)
};

// What a probe at `at` sees: equal-area directions (a Fibonacci sphere), each traced to the
// nearest box face; a face is a back face when the ray meets it from the side its normal
// points away from.
std::vector<ProbeSight> look(glm::vec3 at, const std::vector<Box>& boxes) {
  const int n = 1536;  // as many as a capture's six 16 x 16 faces
  std::vector<ProbeSight> out;
  for (int i = 0; i < n; ++i) {
    const float z = 1.0f - 2.0f * (static_cast<float>(i) + 0.5f) / n;
    const float phi = 2.39996323f * static_cast<float>(i);
    const float r = std::sqrt(1.0f - z * z);
    ProbeSight s;
    s.direction = {r * std::cos(phi), r * std::sin(phi), z};
    s.solidAngle = 4.0f * 3.14159265f / n;
    for (const Box& b : boxes) {
      // Slab test: entry and exit distances.
      float t0 = -1e30f, t1 = 1e30f;
      for (int a = 0; a < 3; ++a) {
        const float d = s.direction[a];
        if (std::abs(d) < 1e-9f) {
          if (at[a] < b.lo[a] || at[a] > b.hi[a]) t0 = 1e30f;
          continue;
        }
        float ta = (b.lo[a] - at[a]) / d, tb = (b.hi[a] - at[a]) / d;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
      }
      if (t0 > t1) continue;
      const bool inside = t0 < 0.0f;
      const float t = inside ? t1 : t0;
      if (t <= 0.0f || t >= s.distance) continue;
      s.distance = t;
      // Leaving a solid (or entering a room's walls from outside) meets a back face.
      s.backface = inside == b.solid;
    }
    out.push_back(s);
  }
  return out;
}

const glm::vec3 kSpacing{1.0f, 1.0f, 1.0f};
// A room far larger than a cell, so its walls are never near.
const Box kRoom{{-10, -10, -10}, {10, 10, 10}, false};

bool inside(glm::vec3 p, const Box& b) {
  return glm::all(glm::greaterThan(p, b.lo)) && glm::all(glm::lessThan(p, b.hi));
}

TEST(ProbeRelocationTest, ABuriedProbeLeavesThroughItsNearestFace) {
  // A block whose top is 0.08 above the probe; its other faces further.
  const Box block{{-0.6f, -0.6f, -0.5f}, {0.6f, 0.08f, 0.5f}, true};
  const glm::vec3 offset = relocateProbe(look({0, 0, 0}, {kRoom, block}), {0, 0, 0}, kSpacing);
  EXPECT_FALSE(inside(offset, block));
  EXPECT_NEAR(offset.y, 0.08f + kProbeClearance, 0.02f);
  EXPECT_NEAR(offset.x, 0.0f, 0.03f);
  EXPECT_NEAR(offset.z, 0.0f, 0.03f);
  // From there it sees the block's top as a front face at the clearance, and stays.
  const glm::vec3 again = relocateProbe(look(offset, {kRoom, block}), offset, kSpacing);
  EXPECT_EQ(again, offset);
}

TEST(ProbeRelocationTest, AProbeAtAWallsNoseStepsBack) {
  // A floor 0.02 below the probe (under half the clearance of 0.1).
  const Box floor{{-10, -10, -10}, {10, -0.02f, 10}, true};
  const glm::vec3 offset = relocateProbe(look({0, 0, 0}, {kRoom, floor}), {0, 0, 0}, kSpacing);
  EXPECT_NEAR(offset.y, kProbeClearance - 0.02f, 0.01f);
  EXPECT_NEAR(offset.x, 0.0f, 0.01f);
  EXPECT_NEAR(offset.z, 0.0f, 0.01f);
}

TEST(ProbeRelocationTest, AClearProbeAndOneAtTheClearanceStay) {
  EXPECT_EQ(relocateProbe(look({0, 0, 0}, {kRoom}), {0, 0, 0}, kSpacing), glm::vec3(0.0f));
  // The outer probes of a grid sit the clearance from a wall on the bounds: not moved.
  const Box wall{{-10, -10, -10}, {-kProbeClearance, 10, 10}, true};
  EXPECT_EQ(relocateProbe(look({0, 0, 0}, {kRoom, wall}), {0, 0, 0}, kSpacing), glm::vec3(0.0f));
  // The previous offset is kept, not pulled back to the grid point.
  const glm::vec3 kept{0.1f, -0.2f, 0.05f};
  EXPECT_EQ(relocateProbe(look(kept, {kRoom}), kept, kSpacing), kept);
}

TEST(ProbeRelocationTest, NoMoveLeavesTheCell) {
  // Buried deep: the nearest face is 0.5 spacing away, beyond the 0.45 a probe may move.
  const Box block{{-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, true};
  EXPECT_EQ(relocateProbe(look({0, 0, 0}, {kRoom, block}), {0, 0, 0}, kSpacing), glm::vec3(0.0f));
  // The same block in a cell twice as wide along y: the probe leaves through the top or the
  // bottom (the x and z faces are as near, but moving along them would leave the cell).
  const glm::vec3 tall{1.0f, 2.0f, 1.0f};
  const Box slab{{-0.5f, -0.45f, -0.5f}, {0.5f, 0.45f, 0.5f}, true};
  const glm::vec3 offset = relocateProbe(look({0, 0, 0}, {kRoom, slab}), {0, 0, 0}, tall);
  EXPECT_NEAR(std::abs(offset.y), 0.45f + kProbeClearance, 0.02f);
  EXPECT_LE(std::abs(offset.y), kProbeMaxOffset * tall.y);
}

TEST(ProbeRelocationTest, AProbeUnderTheGroundRisesAboveIt) {
  // Inside the ground (a studio sweep's floor the grid's lowest layer fell under): back faces
  // everywhere, the nearest straight up.
  const Box ground{{-10, -10, -10}, {10, 0.05f, 10}, true};
  const glm::vec3 offset = relocateProbe(look({0, 0, 0}, {kRoom, ground}), {0, 0, 0}, kSpacing);
  EXPECT_NEAR(offset.y, 0.05f + kProbeClearance, 0.01f);
  // Sky everywhere: nothing to move from.
  EXPECT_EQ(relocateProbe(look({0, 0, 0}, {}), {0, 0, 0}, kSpacing), glm::vec3(0.0f));
}

}  // namespace
}  // namespace penumbra::progressive
