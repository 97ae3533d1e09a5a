// Image reading for the wasm build, where OpenImageIO is not available: stb_image decodes
// Radiance HDR, PNG and JPEG from memory (files come from the virtual file system or a fetch).
// There is no EXR writer in this build; PNG and Radiance writing are shared (image_common.cpp).
#include <stb_image.h>

#include <algorithm>
#include <array>
#include <climits>

#include "image/image_internal.h"
#include "penumbra/image.h"

namespace penumbra {

Result<Image> readImageFromMemory(std::span<const uint8_t> bytes, const std::string& nameForErrors,
                                  const ReadOptions& options) {
  const std::string where = "cannot read '" + nameForErrors + "': ";
  if (bytes.empty() || bytes.size() > static_cast<size_t>(INT_MAX)) {
    return makeError(where + (bytes.empty() ? "empty file" : "file too large"));
  }
  const auto* data = bytes.data();
  const int size = static_cast<int>(bytes.size());
  int w = 0;
  int h = 0;
  int c = 0;
  if (!stbi_info_from_memory(data, size, &w, &h, &c)) {
    return makeError(where + "unknown or unsupported image format (" + stbi_failure_reason() + ")");
  }
  if (static_cast<int64_t>(w) * h > options.maxPixels) {
    return makeError(where + "image size " + std::to_string(w) + "x" + std::to_string(h) +
                     " exceeds the limit of " + std::to_string(options.maxPixels) + " pixels");
  }
  const bool hdr = stbi_is_hdr_from_memory(data, size) != 0;
  Image image;
  if (hdr) {
    float* pixels = stbi_loadf_from_memory(data, size, &w, &h, &c, 0);
    if (!pixels) return makeError(where + stbi_failure_reason());
    image = Image(w, h, c);
    std::copy(pixels, pixels + image.pixels.size(), image.pixels.begin());
    stbi_image_free(pixels);
    return image;
  }
  // 8-bit (or 16-bit PNG reduced to 8 bits): normalise, and sRGB-decode the colour channels.
  stbi_uc* pixels = stbi_load_from_memory(data, size, &w, &h, &c, 0);
  if (!pixels) return makeError(where + stbi_failure_reason());
  image = Image(w, h, c);
  std::array<float, 256> table{};
  for (int i = 0; i < 256; ++i) {
    const float v = static_cast<float>(i) / 255.0f;
    table[i] = options.srgbToLinear ? srgbToLinear(v) : v;
  }
  const bool hasAlpha = c == 2 || c == 4;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const bool isAlpha = hasAlpha && static_cast<int>(i % c) == c - 1;
    image.pixels[i] = isAlpha ? static_cast<float>(pixels[i]) / 255.0f : table[pixels[i]];
  }
  stbi_image_free(pixels);
  return image;
}

Result<Image> readImage(const std::string& path, const ReadOptions& options) {
  auto bytes = detail::readFileBytes(path);
  if (!bytes) return bytes.error();
  return readImageFromMemory(*bytes, path, options);
}

namespace detail {

Status writeExrFile(const std::string&, const std::string& finalPathForErrors, const Image&) {
  return makeError("cannot write '" + finalPathForErrors +
                   "': EXR output is not available in the web build (use .hdr or .png)");
}

}  // namespace detail
}  // namespace penumbra
