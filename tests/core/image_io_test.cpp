// Image I/O: PNG / EXR / HDR round trips, reading from memory, the RGBE codec, atomic writes
// that leave nothing behind on failure, one-line errors naming the file, and compareImages.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "image/image_internal.h"
#include "image/rgbe.h"
#include "penumbra/image.h"
#include "test_support.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> listDir(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

Image gradient(int w, int h, int c, float scale) {
  Image image(w, h, c);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int k = 0; k < c; ++k) {
        image.pixel(x, y)[k] = scale * static_cast<float>((x * 7 + y * 13 + k * 5) % 97) / 96.0f;
      }
    }
  }
  return image;
}

TEST(ImageIoTest, SrgbCurvesAreInverse) {
  for (float v = 0.0f; v <= 1.0f; v += 1.0f / 64) {
    EXPECT_NEAR(srgbToLinear(linearToSrgb(v)), v, 1e-5f);
  }
  EXPECT_NEAR(linearToSrgb(0.18f), 0.4614f, 1e-3f);
  EXPECT_FLOAT_EQ(srgbToLinear(0.0f), 0.0f);
  EXPECT_NEAR(srgbToLinear(1.0f), 1.0f, 1e-6f);
}

TEST(ImageIoTest, PngRoundTrip) {
  const std::string dir = test::freshOutputDir("image_io/png");
  const Image image = gradient(17, 9, 4, 1.0f);
  ASSERT_TRUE(writeImage(dir + "/a.png", image).ok());
  auto raw = readImage(dir + "/a.png", {.srgbToLinear = false});
  ASSERT_TRUE(raw.ok()) << raw.message();
  ASSERT_EQ(raw->width, 17);
  ASSERT_EQ(raw->height, 9);
  ASSERT_EQ(raw->channels, 4);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    EXPECT_NEAR(raw->pixels[i], image.pixels[i], 0.5f / 255.0f + 1e-6f);
  }
  // sRGB-encoded on write, decoded on read: back to linear (alpha untouched).
  ASSERT_TRUE(writeImage(dir + "/b.png", image, {.srgbEncode = true}).ok());
  auto linear = readImage(dir + "/b.png");
  ASSERT_TRUE(linear.ok());
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    EXPECT_NEAR(linear->pixels[i], image.pixels[i], 0.01f) << i;
  }
  EXPECT_EQ(listDir(dir), (std::vector<std::string>{"a.png", "b.png"}));
}

TEST(ImageIoTest, ExrRoundTripIsHalfPrecision) {
  const std::string dir = test::freshOutputDir("image_io/exr");
  Image image = gradient(12, 6, 3, 1000.0f);
  image.pixel(0, 0)[0] = 1e-3f;
  ASSERT_TRUE(writeImage(dir + "/a.exr", image).ok());
  auto back = readImage(dir + "/a.exr");
  ASSERT_TRUE(back.ok()) << back.message();
  ASSERT_EQ(back->channels, 3);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    EXPECT_NEAR(back->pixels[i], image.pixels[i], 1e-3f * image.pixels[i] + 1e-6f);
  }
}

TEST(ImageIoTest, HdrRoundTripAndReaderAgreement) {
  const std::string dir = test::freshOutputDir("image_io/hdr");
  Image image = gradient(40, 5, 3, 50.0f);
  image.pixel(3, 2)[1] = 1e5f;
  ASSERT_TRUE(writeImage(dir + "/a.hdr", image).ok());
  auto back = readImage(dir + "/a.hdr");
  ASSERT_TRUE(back.ok()) << back.message();
  auto bytes = detail::readFileBytes(dir + "/a.hdr");
  ASSERT_TRUE(bytes.ok());
  auto ours = rgbe::decodeFile(*bytes, "a.hdr");
  ASSERT_TRUE(ours.ok()) << ours.message();
  int w = 0, h = 0, c = 0;
  float* stb =
      stbi_loadf_from_memory(bytes->data(), static_cast<int>(bytes->size()), &w, &h, &c, 3);
  ASSERT_NE(stb, nullptr);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    // RGBE keeps 8 bits of mantissa relative to the pixel's largest channel.
    const float largest = std::max(
        {image.pixels[i - i % 3], image.pixels[i - i % 3 + 1], image.pixels[i - i % 3 + 2]});
    EXPECT_NEAR(back->pixels[i], image.pixels[i], largest / 256.0f + 1e-6f);
    EXPECT_EQ(back->pixels[i], ours->image.pixels[i]);  // every reader sees the same floats
    EXPECT_EQ(stb[i], ours->image.pixels[i]);
  }
  stbi_image_free(stb);
}

TEST(ImageIoTest, ReadFromMemory) {
  const Image image = gradient(8, 8, 3, 1.0f);
  auto png = encodePng(image);
  ASSERT_TRUE(png.ok());
  auto fromPng = readImageFromMemory(*png, "mem.png", {.srgbToLinear = false});
  ASSERT_TRUE(fromPng.ok()) << fromPng.message();
  EXPECT_NEAR(fromPng->pixel(5, 3)[1], image.pixel(5, 3)[1], 0.5f / 255.0f + 1e-6f);
  const std::vector<uint8_t> hdr = rgbe::encodeFile(image);
  auto fromHdr = readImageFromMemory(hdr, "mem.hdr");
  ASSERT_TRUE(fromHdr.ok()) << fromHdr.message();
  EXPECT_NEAR(fromHdr->pixel(5, 3)[1], image.pixel(5, 3)[1], 1.0f / 128.0f);
  const std::vector<uint8_t> junk = {1, 2, 3, 4, 5, 6, 7, 8};
  auto bad = readImageFromMemory(junk, "junk.bin");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("junk.bin"), std::string::npos);
}

TEST(ImageIoTest, ErrorsAreOneLineAndNameTheFile) {
  const std::string dir = test::freshOutputDir("image_io/errors");
  auto missing = readImage(dir + "/nope.exr");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.message(), "cannot read '" + dir + "/nope.exr': no such file");
  { std::ofstream(dir + "/garbage.png") << "this is not a png"; }
  auto garbage = readImage(dir + "/garbage.png");
  ASSERT_FALSE(garbage.ok());
  EXPECT_NE(garbage.message().find("garbage.png"), std::string::npos);
  auto folder = readImage(dir);
  ASSERT_FALSE(folder.ok());
  EXPECT_NE(folder.message().find("folder"), std::string::npos);
  ASSERT_TRUE(writeImage(dir + "/big.png", Image(64, 64, 3)).ok());
  auto tooBig = readImage(dir + "/big.png", {.maxPixels = 1000});
  ASSERT_FALSE(tooBig.ok());
  EXPECT_NE(tooBig.message().find("64x64"), std::string::npos);
  auto noFolder = writeImage(dir + "/no/such/folder/x.png", Image(2, 2, 3));
  ASSERT_FALSE(noFolder.ok());
  EXPECT_NE(noFolder.message().find("does not exist"), std::string::npos);
  auto badExt = writeImage(dir + "/x.bmpx", Image(2, 2, 3));
  ASSERT_FALSE(badExt.ok());
  EXPECT_NE(badExt.message().find(".bmpx"), std::string::npos);
  EXPECT_FALSE(writeImage(dir + "/empty.png", Image()).ok());
  for (const Status* s : {&noFolder, &badExt}) {
    EXPECT_EQ(s->message().find('\n'), std::string::npos);
  }
  EXPECT_EQ(missing.message().find('\n'), std::string::npos);
  EXPECT_EQ(garbage.message().find('\n'), std::string::npos);
}

TEST(ImageIoTest, AtomicWriteLeavesNoTemporaryOnFailure) {
  const std::string dir = test::freshOutputDir("image_io/atomic");
  const std::string target = dir + "/out.hdr";
  ASSERT_TRUE(detail::writeFileAtomic(target, std::vector<uint8_t>{1, 2, 3}).ok());
  // A writer that fails half-way: the previous file stays, no temporary remains.
  std::string seenTemp;
  Status failed = detail::writeAtomic(target, [&](const std::string& temp) -> Status {
    seenTemp = temp;
    std::ofstream(temp, std::ios::binary) << "partial";
    return makeError("simulated failure");
  });
  ASSERT_FALSE(failed.ok());
  EXPECT_EQ(failed.message(), "simulated failure");
  EXPECT_EQ(seenTemp.rfind(target + ".tmp-", 0), 0u) << seenTemp;  // same folder, PATH.tmp-*
  EXPECT_EQ(listDir(dir), std::vector<std::string>{"out.hdr"});
  auto kept = detail::readFileBytes(target);
  ASSERT_TRUE(kept.ok());
  EXPECT_EQ(*kept, (std::vector<uint8_t>{1, 2, 3}));
  // A failing real writer: EXR of a target that is a folder.
  fs::create_directories(dir + "/dir.exr");
  EXPECT_FALSE(writeImage(dir + "/dir.exr", Image(2, 2, 3)).ok());
  EXPECT_EQ(listDir(dir), (std::vector<std::string>{"dir.exr", "out.hdr"}));
}

TEST(ImageIoTest, CompareImagesReportsDifferencesAndHeatmap) {
  Image a(4, 3, 3, 0.5f);
  Image b = a;
  auto same = compareImages(a, b);
  ASSERT_TRUE(same.ok());
  EXPECT_EQ(same->maxAbs, 0.0);
  b.pixel(2, 1)[1] = 0.9f;
  auto diff = compareImages(a, b);
  ASSERT_TRUE(diff.ok());
  EXPECT_NEAR(diff->maxAbs, 0.4, 1e-6);
  EXPECT_NEAR(diff->meanAbs, 0.4 / 36.0, 1e-6);
  EXPECT_NEAR(diff->rmse, std::sqrt(0.16 / 36.0), 1e-6);
  ASSERT_EQ(diff->heatmap.width, 4);
  EXPECT_FLOAT_EQ(diff->heatmap.pixel(2, 1)[0], 1.0f);  // the largest difference is red
  EXPECT_FLOAT_EQ(diff->heatmap.pixel(2, 1)[1], 0.0f);
  EXPECT_FLOAT_EQ(diff->heatmap.pixel(0, 0)[0], 0.0f);
  // RGBA against RGB compares RGB only; different sizes are an error.
  Image rgba(4, 3, 4, 0.5f);
  EXPECT_TRUE(compareImages(a, rgba).ok());
  EXPECT_FALSE(compareImages(a, Image(3, 3, 3)).ok());
}

TEST(ImageRgbeTest, PixelCodecIsAFixedPoint) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> mantissa(0.0f, 1.0f);
  std::uniform_int_distribution<int> exponent(-40, 40);
  for (int i = 0; i < 200000; ++i) {
    const float scale = std::ldexp(1.0f, exponent(rng));
    const float r = mantissa(rng) * scale;
    const float g = mantissa(rng) * scale;
    const float b = (i % 7 == 0 ? 0.0f : mantissa(rng)) * scale;
    uint8_t first[4];
    rgbe::encodePixel(r, g, b, first);
    float decoded[3];
    rgbe::decodePixel(first, decoded);
    uint8_t second[4];
    rgbe::encodePixel(decoded[0], decoded[1], decoded[2], second);
    ASSERT_EQ(std::memcmp(first, second, 4), 0) << r << " " << g << " " << b;
    float again[3];
    rgbe::decodePixel(second, again);
    ASSERT_EQ(std::memcmp(decoded, again, sizeof decoded), 0);
    // Round to nearest: within half a mantissa step, at most largest / 256 (a little more
    // when rounding the largest channel up moved the exponent).
    const float largest = std::max({r, g, b});
    if (largest > 1e-30f) {
      ASSERT_NEAR(decoded[0], r, largest / 256.0f * 1.01f);
    }
  }
  uint8_t p[4];
  rgbe::encodePixel(std::nanf(""), -1.0f, 0.0f, p);
  EXPECT_EQ(p[3], 0);
  rgbe::encodePixel(0.999999f, 0.0f, 0.0f, p);  // rounds up to 1.0: the exponent moves
  float v[3];
  rgbe::decodePixel(p, v);
  EXPECT_EQ(v[0], 1.0f);
}

TEST(ImageRgbeTest, DecodesFlatAndOldStyleRunLengthScanlines) {
  // 3 pixels wide (too narrow for new-style RLE): flat, with an old-style run (1,1,1,n).
  std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 3\n";
  std::vector<uint8_t> bytes(header.begin(), header.end());
  for (uint8_t b : {128, 64, 32, 129, 1, 1, 1, 2}) bytes.push_back(b);
  auto decoded = rgbe::decodeFile(bytes, "old.hdr");
  ASSERT_TRUE(decoded.ok()) << decoded.message();
  for (int x = 0; x < 3; ++x) {
    EXPECT_FLOAT_EQ(decoded->image.pixel(x, 0)[0], 1.0f);
    EXPECT_FLOAT_EQ(decoded->image.pixel(x, 0)[1], 0.5f);
    EXPECT_FLOAT_EQ(decoded->image.pixel(x, 0)[2], 0.25f);
  }
}

TEST(ImageRgbeTest, RunLengthEncodingRoundTripsAndCompresses) {
  Image image(300, 4, 3, 0.0f);  // long runs of black, then noise
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 4.0f);
  for (int y = 0; y < 4; ++y) {
    for (int x = 150; x < 300; ++x) {
      for (int k = 0; k < 3; ++k) image.pixel(x, y)[k] = u(rng);
    }
  }
  const std::vector<uint8_t> bytes = rgbe::encodeFile(image);
  EXPECT_LT(bytes.size(), 300u * 4 * 4 * 3 / 4);
  auto decoded = rgbe::decodeFile(bytes, "rle.hdr");
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(rgbe::encodeFile(decoded->image), bytes);
}

TEST(ImageRgbeTest, CorruptDataIsAnError) {
  const std::vector<uint8_t> good = rgbe::encodeFile(gradient(32, 8, 3, 3.0f));
  for (size_t cut : {size_t{5}, size_t{30}, good.size() / 2, good.size() - 1}) {
    auto r = rgbe::decodeFile(std::span(good).first(cut), "cut.hdr");
    EXPECT_FALSE(r.ok()) << cut;
    if (!r.ok()) {
      EXPECT_NE(r.message().find("cut.hdr"), std::string::npos);
    }
  }
  std::string forged = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n";
  auto huge = rgbe::decodeFile(std::vector<uint8_t>(forged.begin(), forged.end()), "forged.hdr");
  ASSERT_FALSE(huge.ok());
  EXPECT_NE(huge.message().find("100000x100000 pixels is more than the 268 million allowed"),
            std::string::npos)
      << huge.message();
  std::string xyze = "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n\x80\x80\x80\x80";
  auto unsupported = rgbe::decodeFile(std::vector<uint8_t>(xyze.begin(), xyze.end()), "xyz.hdr");
  ASSERT_FALSE(unsupported.ok());
  EXPECT_NE(unsupported.message().find("xyze"), std::string::npos);
}

// maxWidth: a wide image is box-filtered by an integer factor as it decodes; each output
// pixel is the mean of its block (the last blocks take the remainder), so the mean radiance
// and a bright spot's flux are kept.
TEST(ImageRgbeTest, WideImagesAreBoxFilteredWhileDecoding) {
  Image image(103, 50, 3, 0.25f);  // 103 = 3 x 34 + 1: the last column of blocks is wider
  image.pixel(40, 20)[0] = 900.0f;  // a small sun in red
  for (int x = 0; x < 103; ++x) image.pixel(x, 49)[1] = static_cast<float>(x) / 102.0f;
  const std::vector<uint8_t> bytes = rgbe::encodeFile(image);
  auto full = rgbe::decodeFile(bytes, "wide.hdr");
  ASSERT_TRUE(full.ok());
  auto small = rgbe::decodeFile(bytes, "wide.hdr", int64_t{1} << 28, 40);
  ASSERT_TRUE(small.ok()) << small.message();
  ASSERT_EQ(small->image.width, 34);  // factor 3 (103 / 40 rounded up)
  ASSERT_EQ(small->image.height, 16);
  const auto sum = [](const Image& im, int c) {
    double s = 0;
    for (int y = 0; y < im.height; ++y) {
      for (int x = 0; x < im.width; ++x) s += im.pixel(x, y)[c];
    }
    return s;
  };
  // Means are kept where blocks are full; the flux of the spot through the block sizes.
  EXPECT_NEAR(small->image.pixel(5, 5)[2], full->image.pixel(15, 15)[2], 1e-6);
  EXPECT_NEAR(small->image.pixel(40 / 3, 20 / 3)[0] * 9.0,
              full->image.pixel(40, 20)[0] + 8.0 * full->image.pixel(0, 0)[0], 1e-2);
  // The total: each mean times its block's area (3 x 3, the last column 4 wide, the last row
  // 5 tall), within RGBE's 1 % steps.
  double total = 0;
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 34; ++x) {
      total += small->image.pixel(x, y)[0] * (x == 33 ? 4 : 3) * (y == 15 ? 5 : 3);
    }
  }
  EXPECT_NEAR(total, sum(full->image, 0), sum(full->image, 0) * 1e-4);
  // Under the limit: unchanged.
  auto same = rgbe::decodeFile(bytes, "wide.hdr", int64_t{1} << 28, 103);
  ASSERT_TRUE(same.ok());
  EXPECT_EQ(same->image.width, 103);
  EXPECT_EQ(same->image.pixels, full->image.pixels);
}

}  // namespace
}  // namespace penumbra
