// The packed single-file environment: bit-exact round trips, the documented layout, the
// embedded manifest and its sidecar, other readers (stb_image, OpenImageIO) reading the file,
// and clear errors for files that are not packed environments.
#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <glm/gtc/packing.hpp>

#include <cstring>
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

// The KTX 2.0 copy (encodeKtx2Environment) as the specification lays it out: header, index,
// the level index pointing at 8-byte aligned levels stored smallest first, faces in order with
// rows from t = 0, half floats within their precision, the manifest in the key/value data.
TEST(PackedEnvironmentTest, Ktx2CopyFollowsTheSpecification) {
  const PackedEnvironment env = randomEnvironment(16, 3, 5);
  auto bytes = encodeKtx2Environment(env);
  ASSERT_TRUE(bytes.ok()) << bytes.message();
  auto again = encodeKtx2Environment(env);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(*bytes, *again) << "deterministic";
  const std::vector<uint8_t>& b = *bytes;
  auto u32 = [&](size_t at) {
    return uint32_t{b[at]} | uint32_t{b[at + 1]} << 8 | uint32_t{b[at + 2]} << 16 |
           uint32_t{b[at + 3]} << 24;
  };
  auto u64 = [&](size_t at) { return uint64_t{u32(at)} | uint64_t{u32(at + 4)} << 32; };
  const uint8_t identifier[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  ASSERT_GT(b.size(), 80u);
  EXPECT_TRUE(std::equal(identifier, identifier + 12, b.begin()));
  EXPECT_EQ(u32(12), 97u);  // VK_FORMAT_R16G16B16A16_SFLOAT
  EXPECT_EQ(u32(16), 2u);   // typeSize
  EXPECT_EQ(u32(20), 16u);
  EXPECT_EQ(u32(24), 16u);
  EXPECT_EQ(u32(28), 0u);  // depth
  EXPECT_EQ(u32(32), 0u);  // layers
  EXPECT_EQ(u32(36), 6u);  // faces
  EXPECT_EQ(u32(40), 3u);  // levels
  EXPECT_EQ(u32(44), 0u);  // supercompression
  // The data format descriptor right after the level index; its total size leads it.
  const uint32_t dfd = u32(48), dfdLength = u32(52);
  EXPECT_EQ(dfd, 80u + 3 * 24);
  EXPECT_EQ(u32(dfd), dfdLength);
  EXPECT_EQ(dfdLength, 4u + 24 + 4 * 16);
  // Key/value data: "KTXwriter" and the manifest, sorted, NUL-terminated.
  const uint32_t kvd = u32(56), kvdLength = u32(60);
  EXPECT_EQ(kvd, dfd + dfdLength);
  const std::string kv(b.begin() + kvd, b.begin() + kvd + kvdLength);
  const size_t writer = kv.find(std::string("KTXwriter\0", 10));
  const size_t manifestAt = kv.find(std::string(kKtx2ManifestKey) + '\0');
  ASSERT_NE(writer, std::string::npos);
  ASSERT_NE(manifestAt, std::string::npos);
  EXPECT_LT(writer, manifestAt);
  const std::string manifestText(kv.c_str() + manifestAt + std::strlen(kKtx2ManifestKey) + 1);
  auto manifest = packedManifestJson(env);
  ASSERT_TRUE(manifest.ok());
  EXPECT_EQ(manifestText, *manifest);
  EXPECT_EQ(u64(64), 0u);  // no supercompression global data
  // Levels: aligned to 8, smallest first, the last one ending the file.
  uint64_t previousStart = b.size();
  for (int m = 0; m < 3; ++m) {
    const uint64_t start = u64(80 + 24 * m), length = u64(88 + 24 * m);
    const int n = 16 >> m;
    EXPECT_EQ(start % 8, 0u) << m;
    EXPECT_EQ(length, uint64_t(6) * n * n * 8) << m;
    EXPECT_EQ(u64(96 + 24 * m), length) << "uncompressed length";
    EXPECT_LT(start, previousStart) << "level " << m << " stored before level " << m - 1;
    if (m == 0) {
      EXPECT_EQ(start + length, b.size());
    }
    previousStart = start;
    // Every texel of the level, face after face, row after row, as half floats.
    float worst = 0.0f;
    for (int f = 0; f < 6; ++f) {
      const Image& face = env.specular.face(m, f);
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          const size_t at = start + ((static_cast<size_t>(f) * n + y) * n + x) * 8;
          for (int c = 0; c < 4; ++c) {
            const float v =
                glm::unpackHalf1x16(static_cast<uint16_t>(b[at + 2 * c] | b[at + 2 * c + 1] << 8));
            const float want = c < 3 ? face.pixel(x, y)[c] : 1.0f;
            worst = std::max(worst, std::abs(v - want) / std::max(std::abs(want), 6.2e-5f));
          }
        }
      }
    }
    EXPECT_LT(worst, 1.0f / 1024.0f) << "level " << m;
  }
}

}  // namespace
}  // namespace penumbra
