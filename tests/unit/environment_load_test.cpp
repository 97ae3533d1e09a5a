// loadEnvironment's panorama path: a panorama much wider than its faces need is box-filtered
// while it decodes (kPanoramaWidthPerFace) and lights the same, and one over the pixel limit is
// refused by name before it is decoded.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "image/rgbe.h"
#include "penumbra/environment.h"
#include "penumbra/ibl.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

TEST(EnvironmentLoad, AWidePanoramaIsFilteredWhileDecodingAndLightsTheSame) {
  // 512 x 256 for 8-pixel faces: 4 times the 128 pixels kept, so decoded at 128 x 64.
  Image pano(512, 256, 3);
  for (int y = 0; y < pano.height; ++y) {
    for (int x = 0; x < pano.width; ++x) {
      float* p = pano.pixel(x, y);
      p[0] = 0.5f + 0.4f * std::sin(x * 0.05f);
      p[1] = y < 128 ? 1.0f : 0.2f;  // bright sky, dark ground
      p[2] = 0.3f;
    }
  }
  const std::string path = freshOutputDir("environment_load") + "/wide.hdr";
  writeBytes(path, rgbe::encodeFile(pano));
  auto loaded = loadEnvironment(path, {.faceSize = 8, .samples = 16, .sunThreshold = 0.0f});
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  ibl::PrefilterOptions po;
  po.faceSize = 8;
  po.samples = 16;
  po.sunThreshold = 0.0f;
  auto direct = ibl::prefilterCpu(pano, po);  // from the full-size image
  ASSERT_TRUE(direct.ok()) << direct.message();
  // The irradiance (first SH band and the up-down gradient) within RGBE's 1 % steps.
  for (int i : {0, 2}) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(loaded->sh.c[i][c], direct->sh.c[i][c], 0.02 * std::abs(direct->sh.c[0][c]))
          << "coefficient " << i << " channel " << c;
    }
  }
}

TEST(EnvironmentLoad, InStepsItIsTheSameEnvironment) {
  Image pano(256, 128, 3);
  for (int y = 0; y < pano.height; ++y) {
    for (int x = 0; x < pano.width; ++x) {
      float* p = pano.pixel(x, y);
      p[0] = 0.2f + static_cast<float>(x) / 256.0f;
      p[1] = y < 40 ? 3.0f : 0.1f;
      p[2] = 0.5f;
    }
  }
  const std::string path = freshOutputDir("environment_steps") + "/steps.hdr";
  writeBytes(path, rgbe::encodeFile(pano));
  const EnvironmentLoadOptions options{.faceSize = 8, .samples = 16, .sunThreshold = 0.0f};
  auto whole = loadEnvironment(path, options);
  ASSERT_TRUE(whole.ok()) << whole.message();
  auto loader = PanoramaLoader::start(path, options);
  ASSERT_TRUE(loader.ok()) << loader.message();
  EXPECT_EQ(loader->width(), 256);
  int steps = 0;
  while (!loader->done()) {
    ASSERT_TRUE(loader->step(7).ok());
    ++steps;
  }
  EXPECT_EQ(steps, (128 + 6) / 7);
  auto stepped = loader->finish();
  ASSERT_TRUE(stepped.ok()) << stepped.message();
  for (int i = 0; i < 9; ++i) EXPECT_EQ(stepped->sh.c[i], whole->sh.c[i]) << i;
  EXPECT_EQ(stepped->specular.face(0, 2).pixels, whole->specular.face(0, 2).pixels);
  // A truncated file fails at the step that reaches its end, naming it.
  std::vector<uint8_t> bytes = rgbe::encodeFile(pano);
  bytes.resize(bytes.size() * 2 / 3);
  writeBytes(path, bytes);
  auto cut = PanoramaLoader::start(path, options);
  ASSERT_TRUE(cut.ok()) << cut.message();
  Status st;
  while (st.ok() && !cut->done()) st = cut->step(16);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("steps.hdr"), std::string::npos) << st.message();
}

TEST(EnvironmentLoad, APanoramaOverThePixelLimitIsRefusedByName) {
  const std::string head = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n";
  const std::string path = freshOutputDir("environment_limit") + "/huge_sky.hdr";
  writeBytes(path, std::vector<uint8_t>(head.begin(), head.end()));
  auto r = loadEnvironment(path, {.faceSize = 64, .maxPanoramaPixels = int64_t{8192} * 4096});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("huge_sky.hdr"), std::string::npos) << r.message();
  EXPECT_NE(r.message().find("16384x8192 pixels is more than the 33 million allowed"),
            std::string::npos)
      << r.message();
  EXPECT_EQ(r.message().find('\n'), std::string::npos);
}

}  // namespace
}  // namespace penumbra::test
