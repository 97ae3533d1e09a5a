// The packed single-file environment: bit-exact round trips, the documented layout, the
// embedded manifest and its sidecar, other readers (stb_image, OpenImageIO) reading the file,
// and clear errors for files that are not packed environments.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "image/image_internal.h"
#include "image/rgbe.h"
#include "penumbra/environment_format.h"
#include "test_support.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

PackedEnvironment randomEnvironment(int size, int mips, unsigned seed) {
  PackedEnvironment env;
  env.specular = ibl::Cubemap(size, mips);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::uniform_int_distribution<int> e(-12, 14);
  for (auto& level : env.specular.mips) {
    for (Image& face : level) {
      for (float& v : face.pixels) v = u(rng) * std::ldexp(1.0f, e(rng));
    }
  }
  for (int m = 0; m < mips; ++m) env.roughness.push_back(ibl::roughnessForMip(m, mips));
  for (auto& c : env.sh.c) c = glm::vec3(u(rng), -u(rng), u(rng) * 1e3f);
  env.samples = 256;
  env.generator = "penumbra-test 1";
  return env;
}

TEST(PackedEnvironmentTest, BitExactRoundTrip) {
  const PackedEnvironment env = randomEnvironment(16, 5, 1);
  auto first = encodePackedEnvironment(env);
  ASSERT_TRUE(first.ok()) << first.message();
  auto decoded = readPackedEnvironmentFromMemory(*first, "first.hdr");
  ASSERT_TRUE(decoded.ok()) << decoded.message();
  auto second = encodePackedEnvironment(*decoded);
  ASSERT_TRUE(second.ok());
  EXPECT_EQ(*first, *second);  // write -> read -> write: identical bytes
  auto again = readPackedEnvironmentFromMemory(*second, "second.hdr");
  ASSERT_TRUE(again.ok());
  for (int m = 0; m < env.specular.mipCount(); ++m) {
    for (int f = 0; f < ibl::kFaceCount; ++f) {
      // decode -> encode -> decode: identical floats.
      ASSERT_EQ(decoded->specular.face(m, f).pixels, again->specular.face(m, f).pixels);
    }
  }
  EXPECT_EQ(decoded->roughness, env.roughness);
  EXPECT_EQ(decoded->sh.c, env.sh.c);
  EXPECT_EQ(decoded->samples, 256);
  EXPECT_EQ(decoded->generator, "penumbra-test 1");
  // And the first decode is within RGBE precision of the original.
  for (int m = 0; m < env.specular.mipCount(); ++m) {
    const auto& a = env.specular.face(m, 3).pixels;
    const auto& b = decoded->specular.face(m, 3).pixels;
    for (size_t i = 0; i < a.size(); i += 3) {
      const float largest = std::max({a[i], a[i + 1], a[i + 2]});
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(b[i + k], a[i + k], largest / 256.0f);
    }
  }
}

TEST(PackedEnvironmentTest, LayoutMatchesDocumentation) {
  // Width 6 * size, faces +X..-Z left to right, mip m from row size * (2 - 2^(1-m)).
  EXPECT_EQ(packedMipRow(256, 0), 0);
  EXPECT_EQ(packedMipRow(256, 1), 256);
  EXPECT_EQ(packedMipRow(256, 2), 384);
  EXPECT_EQ(packedHeight(256, 7), 508);
  PackedEnvironment env = randomEnvironment(8, 3, 2);
  for (int m = 0; m < 3; ++m) {
    for (int f = 0; f < 6; ++f) {
      for (float& v : env.specular.face(m, f).pixels) v = 0.0f;
      // A unique marker per (mip, face) at texel (1, 0).
      env.specular.face(m, f).pixel(1, 0)[0] = static_cast<float>(1 + m * 6 + f);
    }
  }
  auto bytes = encodePackedEnvironment(env);
  ASSERT_TRUE(bytes.ok());
  int w = 0, h = 0, c = 0;
  float* image =
      stbi_loadf_from_memory(bytes->data(), static_cast<int>(bytes->size()), &w, &h, &c, 3);
  ASSERT_NE(image, nullptr) << stbi_failure_reason();
  ASSERT_EQ(w, 48);
  ASSERT_EQ(h, 8 + 4 + 2);
  for (int m = 0; m < 3; ++m) {
    const int n = 8 >> m;
    for (int f = 0; f < 6; ++f) {
      const int x = f * n + 1;
      const int y = packedMipRow(8, m);
      EXPECT_EQ(image[(y * w + x) * 3], static_cast<float>(1 + m * 6 + f)) << m << " " << f;
    }
  }
  // Texels outside the faces (right of a mip's faces) are black.
  EXPECT_EQ(image[(9 * w + 47) * 3], 0.0f);
  stbi_image_free(image);
}

TEST(PackedEnvironmentTest, ManifestEmbeddedAndBeside) {
  const std::string dir = test::freshOutputDir("packed/manifest");
  const PackedEnvironment env = randomEnvironment(32, 4, 3);
  ASSERT_TRUE(writePackedEnvironment(dir + "/env.hdr", env).ok());
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"env.hdr", "env.json"}));

  std::ifstream sidecar(dir + "/env.json");
  const nlohmann::json j = nlohmann::json::parse(sidecar);
  EXPECT_EQ(j["format"], "penumbra-packed-environment");
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["faceSize"], 32);
  EXPECT_EQ(j["mipCount"], 4);
  EXPECT_EQ(j["width"], 192);
  EXPECT_EQ(j["height"], 60);
  EXPECT_EQ(j["encoding"], "rgbe");
  EXPECT_EQ(j["orientation"], "gl-cubemap");
  EXPECT_EQ(j["faceOrder"], nlohmann::json({"+X", "-X", "+Y", "-Y", "+Z", "-Z"}));
  EXPECT_EQ(j["roughness"].size(), 4u);
  EXPECT_EQ(j["mips"][2]["y"], 48);
  EXPECT_EQ(j["sh"]["coefficients"].size(), 9u);
  EXPECT_EQ(j["generator"], "penumbra-test 1");

  // The same manifest is the PENUMBRA_ENV header line, and a Radiance reader reads the file.
  auto bytes = detail::readFileBytes(dir + "/env.hdr");
  ASSERT_TRUE(bytes.ok());
  auto decoded = rgbe::decodeFile(*bytes, "env.hdr");
  ASSERT_TRUE(decoded.ok());
  bool found = false;
  for (const std::string& line : decoded->headerLines) {
    if (line.rfind("PENUMBRA_ENV=", 0) == 0) {
      found = true;
      EXPECT_EQ(nlohmann::json::parse(line.substr(13)), j);
    }
  }
  EXPECT_TRUE(found);
  auto viaOiio = readImage(dir + "/env.hdr");
  ASSERT_TRUE(viaOiio.ok()) << viaOiio.message();
  EXPECT_EQ(viaOiio->pixels, decoded->image.pixels);
  auto read = readPackedEnvironment(dir + "/env.hdr");
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_EQ(read->specular.faceSize(3), 4);
}

TEST(PackedEnvironmentTest, ManifestLinesOfAnyLengthStayReadable) {
  // Generators of different lengths move the manifest line across the 128-byte boundaries
  // that chunked header readers stumble on.
  for (int extra = 0; extra < 260; ++extra) {
    PackedEnvironment env = randomEnvironment(8, 2, 4);
    env.generator = std::string(extra, 'g');
    auto bytes = encodePackedEnvironment(env);
    ASSERT_TRUE(bytes.ok());
    int w = 0, h = 0, c = 0;
    float* image =
        stbi_loadf_from_memory(bytes->data(), static_cast<int>(bytes->size()), &w, &h, &c, 3);
    ASSERT_NE(image, nullptr) << extra;
    stbi_image_free(image);
    if (extra % 16 == 0 || extra % 128 > 120) {
      auto viaOiio = readImageFromMemory(*bytes, "g.hdr");
      ASSERT_TRUE(viaOiio.ok()) << extra << ": " << viaOiio.message();
    }
    auto back = readPackedEnvironmentFromMemory(*bytes, "g.hdr");
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(back->generator, env.generator);
  }
}

TEST(PackedEnvironmentTest, RejectsOtherFiles) {
  const std::string dir = test::freshOutputDir("packed/reject");
  auto missing = readPackedEnvironment(dir + "/missing.hdr");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.message().find("no such file"), std::string::npos);

  const std::vector<uint8_t> plain = rgbe::encodeFile(Image(48, 14, 3, 1.0f));
  auto noManifest = readPackedEnvironmentFromMemory(plain, "plain.hdr");
  ASSERT_FALSE(noManifest.ok());
  EXPECT_NE(noManifest.message().find("not a Penumbra packed environment"), std::string::npos);

  const auto withManifest = [](const std::string& json, int w, int h) {
    const std::string lines[] = {"PENUMBRA_ENV=" + json};
    return rgbe::encodeFile(Image(w, h, 3, 1.0f), lines);
  };
  PackedEnvironment env = randomEnvironment(8, 2, 5);
  auto manifest = packedManifestJson(env);
  ASSERT_TRUE(manifest.ok());
  auto wrongSize = readPackedEnvironmentFromMemory(withManifest(*manifest, 48, 13), "size.hdr");
  ASSERT_FALSE(wrongSize.ok());
  EXPECT_NE(wrongSize.message().find("48x13"), std::string::npos);
  auto badJson = readPackedEnvironmentFromMemory(withManifest("{not json", 48, 12), "json.hdr");
  ASSERT_FALSE(badJson.ok());
  EXPECT_NE(badJson.message().find("JSON"), std::string::npos);
  nlohmann::json future = nlohmann::json::parse(*manifest);
  future["version"] = kPackedFormatVersion + 1;
  auto newer = readPackedEnvironmentFromMemory(withManifest(future.dump(), 48, 12), "v3.hdr");
  ASSERT_FALSE(newer.ok());
  EXPECT_NE(newer.message().find("newer"), std::string::npos);
  nlohmann::json wrongType = nlohmann::json::parse(*manifest);
  wrongType["faceSize"] = "eight";
  EXPECT_FALSE(
      readPackedEnvironmentFromMemory(withManifest(wrongType.dump(), 48, 12), "t.hdr").ok());
  nlohmann::json shortSh = nlohmann::json::parse(*manifest);
  shortSh["sh"]["coefficients"].erase(0);
  EXPECT_FALSE(
      readPackedEnvironmentFromMemory(withManifest(shortSh.dump(), 48, 12), "sh.hdr").ok());
  // Truncated image data.
  auto good = encodePackedEnvironment(env);
  ASSERT_TRUE(good.ok());
  EXPECT_FALSE(
      readPackedEnvironmentFromMemory(std::span(*good).first(good->size() - 20), "cut.hdr").ok());
  // Invalid environments are refused on write.
  PackedEnvironment broken = env;
  broken.roughness.pop_back();
  EXPECT_FALSE(encodePackedEnvironment(broken).ok());
  EXPECT_FALSE(writePackedEnvironment(dir + "/no/folder/env.hdr", env).ok());
}

}  // namespace
}  // namespace penumbra
