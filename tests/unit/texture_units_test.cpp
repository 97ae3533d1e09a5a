// The texture-unit table (gpu/texture_units.h): a unit per role within WebGL2's 16, and a clear
// error when a context offers fewer.
#include <gtest/gtest.h>

#include "gpu/texture_units.h"
#include "passes/limits.h"

namespace penumbra {
namespace {

TEST(TextureUnitsTest, EveryRoleHasItsOwnUnitWithinSixteen) {
  EXPECT_EQ(kTextureUnitsNeeded, 16);
  EXPECT_EQ(unitOf(TextureUnit::BaseColor), 0);
  EXPECT_LT(unitOf(TextureUnit::MaterialLayers), 16);
  // The aliases share units only with roles named in passes/limits.h.
  EXPECT_EQ(passes::kUnitBehind, unitOf(TextureUnit::OcclusionRays));
  EXPECT_EQ(passes::kUnitLightCache, unitOf(TextureUnit::PointShadow1));
}

TEST(TextureUnitsTest, TooFewUnitsIsAnErrorNamingBothNumbers) {
  EXPECT_TRUE(checkTextureUnits(16).ok());
  EXPECT_TRUE(checkTextureUnits(32).ok());
  const Status s = checkTextureUnits(8);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("offers 8 texture units"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("needs 16"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace penumbra
