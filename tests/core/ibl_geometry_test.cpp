// Cube-map and panorama geometry: the GL face table, the documented panorama orientation
// (Blender's world-texture convention through its glTF importer), exact texel solid angles,
// and panorama -> cube resampling (orientation of a marked column, area filtering).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <glm/gtc/type_ptr.hpp>

#include "penumbra/ibl.h"

namespace penumbra::ibl {
namespace {

constexpr float kPiF = std::numbers::pi_v<float>;

void expectDir(const glm::vec3& actual, const glm::vec3& expected, const char* what) {
  const glm::vec3 e = glm::normalize(expected);
  EXPECT_NEAR(actual.x, e.x, 1e-5f) << what;
  EXPECT_NEAR(actual.y, e.y, 1e-5f) << what;
  EXPECT_NEAR(actual.z, e.z, 1e-5f) << what;
}

TEST(IblGeometryTest, FaceOrientationMatchesGlTable) {
  // OpenGL ES 3.0 spec, table 3.21 (major axis, sc, tc): s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2.
  // At (s, t) = (0, 0) both sc and tc are -|ma|; at the face centre the direction is the axis.
  expectDir(cubeDirection(kPositiveX, 0, 0), {1, 1, 1}, "+X s=0 t=0 (sc=-rz, tc=-ry)");
  expectDir(cubeDirection(kNegativeX, 0, 0), {-1, 1, -1}, "-X (sc=+rz, tc=-ry)");
  expectDir(cubeDirection(kPositiveY, 0, 0), {-1, 1, -1}, "+Y (sc=+rx, tc=+rz)");
  expectDir(cubeDirection(kNegativeY, 0, 0), {-1, -1, 1}, "-Y (sc=+rx, tc=-rz)");
  expectDir(cubeDirection(kPositiveZ, 0, 0), {-1, 1, 1}, "+Z (sc=+rx, tc=-ry)");
  expectDir(cubeDirection(kNegativeZ, 0, 0), {1, 1, -1}, "-Z (sc=-rx, tc=-ry)");
  expectDir(cubeDirection(kPositiveX, 0.5f, 0.5f), {1, 0, 0}, "+X centre");
  expectDir(cubeDirection(kNegativeY, 0.5f, 0.5f), {0, -1, 0}, "-Y centre");
  expectDir(cubeDirection(kNegativeZ, 0.5f, 0.5f), {0, 0, -1}, "-Z centre");
  // Increasing s and t on +Z: toward +X and toward -Y (row 0 is the top of a side face).
  expectDir(cubeDirection(kPositiveZ, 1, 0.5f), {1, 0, 1}, "+Z s=1");
  expectDir(cubeDirection(kPositiveZ, 0.5f, 1), {0, -1, 1}, "+Z t=1");
  EXPECT_STREQ(faceName(kNegativeY), "-Y");
  EXPECT_STREQ(faceTag(kPositiveZ), "pz");
}

TEST(IblGeometryTest, CubeCoordInvertsCubeDirection) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.01f, 0.99f);
  for (int i = 0; i < 6000; ++i) {
    const int face = i % kFaceCount;
    const float s = u(rng);
    const float t = u(rng);
    const CubeCoord c = cubeCoord(cubeDirection(face, s, t) * 3.0f);  // length does not matter
    EXPECT_EQ(c.face, face);
    EXPECT_NEAR(c.s, s, 1e-5f);
    EXPECT_NEAR(c.t, t, 1e-5f);
  }
}

TEST(IblGeometryTest, TexelSolidAnglesSumToFourPi) {
  for (int size : {1, 2, 7, 32}) {
    double sum = 0.0;
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) sum += texelSolidAngle(x, y, size);
    }
    EXPECT_NEAR(sum * kFaceCount, 4.0 * std::numbers::pi, 1e-9) << size;
  }
  // Corner texels subtend less than centre texels.
  EXPECT_LT(texelSolidAngle(0, 0, 16), texelSolidAngle(8, 8, 16));
}

TEST(IblGeometryTest, SolidAngleTableMatchesPerTexelValuesExactly) {
  // The prefilter's loops use the table; bit-identical output depends on exact equality.
  for (int size : {1, 3, 16}) {
    const std::vector<double> table = texelSolidAngles(size);
    ASSERT_EQ(table.size(), static_cast<size_t>(size * size));
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        EXPECT_EQ(table[static_cast<size_t>(y) * size + x], texelSolidAngle(x, y, size))
            << x << "," << y;
      }
    }
  }
}

TEST(IblGeometryTest, PanoramaConventionIsDocumented) {
  expectDir(panoramaDirection(0.5f, 0.5f), {1, 0, 0}, "centre column = +X");
  expectDir(panoramaDirection(0.75f, 0.5f), {0, 0, 1}, "u = 0.75 = +Z");
  expectDir(panoramaDirection(0.25f, 0.5f), {0, 0, -1}, "u = 0.25 = -Z");
  expectDir(panoramaDirection(0.0f, 0.5f), {-1, 0, 0}, "left edge = -X");
  expectDir(panoramaDirection(0.3f, 0.0f), {0, 1, 0}, "top row = +Y");
  expectDir(panoramaDirection(0.3f, 1.0f), {0, -1, 0}, "bottom row = -Y");
}

TEST(IblGeometryTest, PanoramaMatchesBlenderThroughGltfImporter) {
  // Cycles: u = (atan2(b.y, b.x) - pi) / (-2 pi), v = (acos(b.z) - pi) / (-pi) with v = 1 at
  // the image top; Blender's glTF importer maps glTF (x, y, z) to Blender (x, -z, y).
  std::mt19937 rng(5);
  std::normal_distribution<float> normal;
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 d = glm::normalize(glm::vec3(normal(rng), normal(rng), normal(rng)));
    const glm::vec3 b(d.x, -d.z, d.y);
    float uBlender = (std::atan2(b.y, b.x) - kPiF) / (-2.0f * kPiF);
    if (uBlender >= 1.0f) uBlender -= 1.0f;
    const float vBlender = (std::acos(b.z) - kPiF) / (-kPiF);
    const glm::vec2 uv = panoramaCoord(d);
    const float du = std::fabs(uv.x - uBlender);
    EXPECT_LT(std::min(du, 1.0f - du), 1e-5f);
    EXPECT_NEAR(uv.y, 1.0f - vBlender, 1e-5f);  // our v counts rows from the top
    expectDir(panoramaDirection(uv.x, uv.y), d, "round trip");
  }
}

TEST(IblGeometryTest, MarkedColumnsLandOnDocumentedFaces) {
  // Red column at u = 0.75 (+Z), green at u = 0.5 (+X), blue top rows (+Y).
  Image pano(256, 128, 3, 0.0f);
  for (int y = 0; y < pano.height; ++y) {
    for (int x = 0; x < pano.width; ++x) {
      float* p = pano.pixel(x, y);
      if (x >= 188 && x < 196) p[0] = 1.0f;  // u in [0.734, 0.766)
      if (x >= 124 && x < 132) p[1] = 1.0f;  // u in [0.484, 0.516)
      if (y < 8) p[2] = 1.0f;                // elevation above ~79 degrees
    }
  }
  auto cube = panoramaToCubemap(pano, 32);
  ASSERT_TRUE(cube.ok()) << cube.message();
  const auto at = [&](int face, int x, int y) {
    return glm::make_vec3(cube->face(0, face).pixel(x, y));
  };
  // The centre columns of +Z and +X faces carry the marks; their horizons are in the middle.
  EXPECT_GT(at(kPositiveZ, 16, 16).x, 0.9f);
  EXPECT_LT(at(kPositiveZ, 16, 16).y, 0.1f);
  EXPECT_GT(at(kPositiveX, 15, 20).y, 0.9f);
  EXPECT_LT(at(kPositiveX, 15, 20).x, 0.1f);
  EXPECT_LT(at(kNegativeZ, 16, 16).x + at(kNegativeZ, 16, 16).y, 0.1f);
  EXPECT_GT(at(kPositiveY, 16, 16).z, 0.9f);
  EXPECT_LT(at(kNegativeY, 16, 16).z, 0.1f);
  // sampleCubemap agrees with the panorama in the marked directions.
  EXPECT_GT(sampleCubemap(*cube, 0, {0, 0, 1}).x, 0.9f);
  EXPECT_GT(sampleCubemap(*cube, 0, {1, 0, 0}).y, 0.9f);
}

TEST(IblGeometryTest, ConstantPanoramaGivesConstantCube) {
  Image pano(64, 32, 3, 0.0f);
  for (size_t i = 0; i < pano.pixels.size(); i += 3) {
    pano.pixels[i] = 0.25f, pano.pixels[i + 1] = 1.5f, pano.pixels[i + 2] = 7.0f;
  }
  for (int size : {4, 16, 64}) {
    auto cube = panoramaToCubemap(pano, size);
    ASSERT_TRUE(cube.ok());
    for (int f = 0; f < kFaceCount; ++f) {
      for (float v : cube->face(0, f).pixels) EXPECT_TRUE(v == 0.25f || v == 1.5f || v == 7.0f);
    }
  }
}

TEST(IblGeometryTest, MinificationIsAreaFiltered) {
  // A one-pixel checkerboard of 0 and 1: a point-sampled cube would alias to 0s and 1s, an
  // area-filtered one is close to the mean everywhere.
  Image pano(2048, 1024, 1, 0.0f);
  for (int y = 0; y < pano.height; ++y) {
    for (int x = 0; x < pano.width; ++x) pano.pixel(x, y)[0] = ((x + y) & 1) ? 1.0f : 0.0f;
  }
  auto cube = panoramaToCubemap(pano, 16);
  ASSERT_TRUE(cube.ok());
  for (int f = 0; f < kFaceCount; ++f) {
    for (float v : cube->face(0, f).pixels) EXPECT_NEAR(v, 0.5f, 0.05f);
  }
}

TEST(IblGeometryTest, PanoramaErrors) {
  auto notTwoToOne = panoramaToCubemap(Image(1000, 700, 3), 16);
  ASSERT_FALSE(notTwoToOne.ok());
  EXPECT_EQ(notTwoToOne.message(), "expected a 2:1 equirectangular panorama, got 1000x700");
  auto badSize = panoramaToCubemap(Image(64, 32, 3), 24);
  ASSERT_FALSE(badSize.ok());
  EXPECT_NE(badSize.message().find("power of two"), std::string::npos);
}

TEST(IblGeometryTest, SanitizeClampsAndCounts) {
  Image image(4, 1, 4, 1.0f);
  image.pixel(0, 0)[0] = std::nanf("");
  image.pixel(1, 0)[1] = -2.0f;
  image.pixel(2, 0)[2] = INFINITY;
  image.pixel(3, 0)[3] = -1.0f;  // alpha is not radiance: left alone
  EXPECT_EQ(sanitizeRadiance(image).replaced, 3);
  EXPECT_EQ(image.pixel(0, 0)[0], 0.0f);
  EXPECT_EQ(image.pixel(1, 0)[1], 0.0f);
  EXPECT_EQ(image.pixel(2, 0)[2], 65504.0f);
  EXPECT_EQ(image.pixel(3, 0)[3], -1.0f);
  EXPECT_EQ(sanitizeRadiance(image).replaced, 0);
}

TEST(IblGeometryTest, RadianceVerdictWarnsOrRefuses) {
  Image some(4, 1, 3, 1.0f);
  some.pixel(0, 0)[0] = std::nanf("");
  some.pixel(1, 0)[1] = 1e30f;  // finite but absurd: what an RGBE exponent of 255 decodes to
  const RadianceReport r = sanitizeRadiance(some);
  EXPECT_EQ(r.nan, 1);
  EXPECT_EQ(r.tooBright, 1);
  EXPECT_EQ(some.pixel(1, 0)[1], kMaxRadiance);
  auto warning = radianceVerdict(r, "sky.hdr");
  ASSERT_TRUE(warning.ok());
  EXPECT_NE(warning->find("sky.hdr: replaced 2 of 4 pixels"), std::string::npos) << *warning;
  EXPECT_NE(warning->find("1 NaN"), std::string::npos) << *warning;
  EXPECT_NE(warning->find("1 above 65504"), std::string::npos) << *warning;

  Image none(2, 1, 3, 1e38f);
  auto refused = radianceVerdict(sanitizeRadiance(none), "overflow.hdr");
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.message().find("overflow.hdr: no usable radiance"), std::string::npos);
  EXPECT_EQ(refused.message().find('\n'), std::string::npos);

  Image clean(2, 1, 3, 0.5f);
  auto quiet = radianceVerdict(sanitizeRadiance(clean), "clean.hdr");
  ASSERT_TRUE(quiet.ok());
  EXPECT_TRUE(quiet->empty());
}

TEST(IblGeometryTest, PreviewPanoramaRoundTrip) {
  // A smooth panorama survives panorama -> cube -> panorama closely.
  Image pano(128, 64, 3);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 128; ++x) {
      const glm::vec3 d = panoramaDirection((x + 0.5f) / 128, (y + 0.5f) / 64);
      float* p = pano.pixel(x, y);
      p[0] = 1.0f + d.x, p[1] = 1.0f + d.y, p[2] = 1.0f + d.z;
    }
  }
  auto cube = panoramaToCubemap(pano, 32);
  ASSERT_TRUE(cube.ok());
  const Image back = cubemapToPanorama(*cube, 0, 128);
  ASSERT_EQ(back.width, 128);
  ASSERT_EQ(back.height, 64);
  auto diff = compareImages(pano, back);
  ASSERT_TRUE(diff.ok());
  EXPECT_LT(diff->maxAbs, 0.06);
  EXPECT_LT(diff->meanAbs, 0.01);
}

}  // namespace
}  // namespace penumbra::ibl
