// Image: float pixels in memory, and the one small read/write API that Penumbra uses for every
// image file: Radiance .hdr through Penumbra's own RGBE codec, OpenEXR through the OpenEXR
// library (native builds only), PFM, and PNG, JPEG, BMP, TGA, GIF, PSD and PNM through
// stb_image; PNG written with stb_image_write. Natively and in the wasm build alike.
// Pixels are row-major with row 0 at the top of the picture, channels interleaved.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "penumbra/error.h"

namespace penumbra {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> pixels;

  Image() = default;
  Image(int w, int h, int c, float fill = 0.0f)
      : width(w), height(h), channels(c), pixels(static_cast<size_t>(w) * h * c, fill) {}

  bool empty() const { return pixels.empty(); }
  float* pixel(int x, int y) { return &pixels[(static_cast<size_t>(y) * width + x) * channels]; }
  const float* pixel(int x, int y) const {
    return &pixels[(static_cast<size_t>(y) * width + x) * channels];
  }
};

struct ReadOptions {
  // 8-bit formats (PNG, JPEG) are sRGB-decoded to linear values when true; HDR and EXR are
  // always linear and returned unchanged.
  bool srgbToLinear = true;
  // Refuse images with more pixels than this (bad input, not a crash).
  int64_t maxPixels = int64_t{1} << 28;
  // > 0: a Radiance (.hdr) image wider than this is box-filtered down by an integer factor as it
  // decodes (a panorama prefiltered to small faces needs no more; time and memory).
  int maxWidth = 0;
};

struct WriteOptions {
  // For 8-bit outputs (PNG): encode linear values with the sRGB curve before quantising.
  // Off means the values are already display-encoded and are written as they are.
  bool srgbEncode = false;
};

// Reads an image file. Errors name the file and the reason in one line.
Result<Image> readImage(const std::string& path, const ReadOptions& options = {});
// Reads an encoded image from memory (the wasm build's fetch and drag-and-drop route).
Result<Image> readImageFromMemory(std::span<const uint8_t> bytes, const std::string& nameForErrors,
                                  const ReadOptions& options = {});

// Writes by extension: .png (8-bit, values clamped to [0,1]), .exr (half float),
// .hdr (Radiance RGBE). The file is written under a temporary name in the same folder and
// renamed, so a failed write never leaves a half-written file under the final name.
Status writeImage(const std::string& path, const Image& image, const WriteOptions& options = {});

// Encodes to PNG bytes in memory (screenshots in the browser, tests).
Result<std::vector<uint8_t>> encodePng(const Image& image, const WriteOptions& options = {});

// sRGB transfer functions (IEC 61966-2-1), shared by the image code and the tests.
float srgbToLinear(float v);
float linearToSrgb(float v);

// Image comparison for tests and evaluation: per-channel absolute differences over RGB only.
struct ImageDiff {
  double maxAbs = 0.0;
  double meanAbs = 0.0;
  double rmse = 0.0;
  Image heatmap;  // RGB visualisation of the per-pixel difference, scaled so maxAbs is red
};
Result<ImageDiff> compareImages(const Image& a, const Image& b);

}  // namespace penumbra
