// The parts of the image API that are the same in the native and the web build: sRGB curves,
// RGBA8 resampling (stb_image_resize), image comparison, PNG encoding (stb_image_write),
// Radiance writing (our own RGBE codec), and the dispatch of writeImage by extension.
#include <stb_image_resize.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>

#include "image/image_internal.h"
#include "image/resize.h"
#include "image/rgbe.h"
#include "penumbra/image.h"

namespace penumbra {

std::vector<uint8_t> resizeRgba8(const std::vector<uint8_t>& pixels, int w, int h, int nw, int nh) {
  std::vector<uint8_t> out(static_cast<size_t>(nw) * static_cast<size_t>(nh) * 4);
  stbir_resize_uint8(pixels.data(), w, h, 0, out.data(), nw, nh, 0, 4);
  return out;
}

float srgbToLinear(float v) {
  if (v <= 0.04045f) return v / 12.92f;
  return std::pow((v + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float v) {
  if (v <= 0.0031308f) return v * 12.92f;
  return 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

Result<std::vector<uint8_t>> encodePng(const Image& image, const WriteOptions& options) {
  if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height * image.channels) {
    return makeError("cannot encode PNG: invalid image (" + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + ", " + std::to_string(image.channels) +
                     " channels)");
  }
  const int c = image.channels;
  const bool hasAlpha = c == 2 || c == 4;
  std::vector<uint8_t> bytes(image.pixels.size());
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    float v = image.pixels[i];
    if (!(v > 0.0f)) v = 0.0f;  // NaN too
    v = std::min(v, 1.0f);
    const bool isAlpha = hasAlpha && static_cast<int>(i % c) == c - 1;
    if (options.srgbEncode && !isAlpha) v = linearToSrgb(v);
    bytes[i] = static_cast<uint8_t>(v * 255.0f + 0.5f);
  }
  std::vector<uint8_t> png;
  const auto sink = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    const auto* p = static_cast<const uint8_t*>(data);
    out->insert(out->end(), p, p + size);
  };
  if (!stbi_write_png_to_func(sink, &png, image.width, image.height, c, bytes.data(),
                              image.width * c)) {
    return makeError("cannot encode PNG: stb_image_write failed");
  }
  return png;
}

Status writeImage(const std::string& path, const Image& image, const WriteOptions& options) {
  if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height * image.channels) {
    return makeError("cannot write '" + path + "': invalid image");
  }
  const std::string ext = detail::lowerExtension(path);
  if (ext == ".png") {
    auto png = encodePng(image, options);
    if (!png) return makeError("cannot write '" + path + "': " + png.message());
    return detail::writeFileAtomic(path, *png);
  }
  if (ext == ".hdr") {
    return detail::writeFileAtomic(path, rgbe::encodeFile(image));
  }
  if (ext == ".exr") {
    return detail::writeAtomic(
        path, [&](const std::string& temp) { return detail::writeExrFile(temp, path, image); });
  }
  return makeError("cannot write '" + path + "': unsupported format '" + ext +
                   "' (use .png, .exr or .hdr)");
}

Result<ImageDiff> compareImages(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) {
    return makeError("cannot compare images of different sizes: " + std::to_string(a.width) + "x" +
                     std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                     std::to_string(b.height));
  }
  if (a.empty()) return makeError("cannot compare empty images");
  const int ca = std::min(a.channels, 3);
  const int cb = std::min(b.channels, 3);
  if (ca != cb) {
    return makeError("cannot compare images with " + std::to_string(a.channels) + " and " +
                     std::to_string(b.channels) + " channels");
  }
  ImageDiff diff;
  const size_t n = static_cast<size_t>(a.width) * a.height;
  std::vector<float> perPixel(n, 0.0f);
  double sum = 0.0;
  double sumSq = 0.0;
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < ca; ++c) {
      const double d = std::fabs(static_cast<double>(a.pixels[i * a.channels + c]) -
                                 b.pixels[i * b.channels + c]);
      const double dd = std::isnan(d) ? 1e30 : d;  // a NaN on one side is a maximal difference
      sum += dd;
      sumSq += dd * dd;
      diff.maxAbs = std::max(diff.maxAbs, dd);
      perPixel[i] = std::max(perPixel[i], static_cast<float>(dd));
    }
  }
  const double count = static_cast<double>(n) * ca;
  diff.meanAbs = sum / count;
  diff.rmse = std::sqrt(sumSq / count);
  // Heat map: black (equal) through blue, green and yellow to red (the largest difference).
  diff.heatmap = Image(a.width, a.height, 3);
  const float scale = diff.maxAbs > 0.0 ? static_cast<float>(1.0 / diff.maxAbs) : 0.0f;
  for (size_t i = 0; i < n; ++i) {
    const float t = std::clamp(perPixel[i] * scale, 0.0f, 1.0f);
    float* p = &diff.heatmap.pixels[i * 3];
    const auto set = [p](float r, float g, float bl) { p[0] = r, p[1] = g, p[2] = bl; };
    if (t < 0.25f) {
      set(0.0f, 0.0f, t * 4.0f);
    } else if (t < 0.5f) {
      set(0.0f, (t - 0.25f) * 4.0f, 1.0f - (t - 0.25f) * 4.0f);
    } else if (t < 0.75f) {
      set((t - 0.5f) * 4.0f, 1.0f, 0.0f);
    } else {
      set(1.0f, 1.0f - (t - 0.75f) * 4.0f, 0.0f);
    }
  }
  return diff;
}

}  // namespace penumbra
