// Image reading, the same in the native and the web build apart from OpenEXR (native only,
// exr_native.cpp): the first bytes choose the decoder.
//   Radiance "#?"      Penumbra's own RGBE codec (image/rgbe.h), as the packed format uses
//   OpenEXR            detail::readExr (the OpenEXR library; the web build refuses)
//   PFM "PF" / "Pf"    below: three header lines and raw 32-bit floats, rows bottom-up
//   anything else      stb_image (PNG 8 and 16 bit, JPEG, BMP, TGA, GIF, PSD, PNM)
// 8- and 16-bit data are normalised and, with ReadOptions::srgbToLinear, sRGB-decoded (alpha
// stays linear). No OpenImageIO: linking it costs every short-lived tool about 0.28 s and
// 130 MB of start-up (its 260 shared libraries), more than the work of most runs.
#include <stb_image.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstring>
#include <string>

#include "image/image_internal.h"
#include "image/rgbe.h"
#include "penumbra/image.h"

namespace penumbra {
namespace {

bool startsWith(std::span<const uint8_t> b, std::initializer_list<uint8_t> magic) {
  return b.size() >= magic.size() && std::equal(magic.begin(), magic.end(), b.begin());
}

Status checkSize(int64_t w, int64_t h, const std::string& where, const ReadOptions& options) {
  if (w <= 0 || h <= 0) return makeError(where + "empty image");
  if (w * h > options.maxPixels) {
    return makeError(where + "image size " + std::to_string(w) + "x" + std::to_string(h) +
                     " exceeds the limit of " + std::to_string(options.maxPixels) + " pixels");
  }
  return {};
}

// Portable float map: "PF" (RGB) or "Pf" (grey), "W H", a scale whose sign gives the byte
// order (negative: little-endian), then rows from the bottom up.
Result<Image> decodePfm(std::span<const uint8_t> b, const std::string& where,
                        const ReadOptions& options) {
  size_t pos = 0;
  auto token = [&]() {
    while (pos < b.size() && std::isspace(b[pos])) ++pos;
    std::string t;
    while (pos < b.size() && !std::isspace(b[pos]) && t.size() < 32)
      t += static_cast<char>(b[pos++]);
    return t;
  };
  const std::string kind = token(), ws = token(), hs = token(), ss = token();
  ++pos;  // the single whitespace byte before the data
  char* end = nullptr;
  const long w = std::strtol(ws.c_str(), &end, 10);
  const bool wOk = !ws.empty() && *end == 0;
  const long h = std::strtol(hs.c_str(), &end, 10);
  const bool hOk = !hs.empty() && *end == 0;
  const double scale = std::strtod(ss.c_str(), &end);
  if (!wOk || !hOk || ss.empty() || *end != 0 || scale == 0.0 || !std::isfinite(scale)) {
    return makeError(where + "malformed PFM header");
  }
  PN_TRY(checkSize(w, h, where, options));
  const int c = kind == "PF" ? 3 : 1;
  const uint64_t need = static_cast<uint64_t>(w) * static_cast<uint64_t>(h) * c * 4;
  if (pos > b.size() || b.size() - pos < need) return makeError(where + "truncated PFM data");
  Image image(static_cast<int>(w), static_cast<int>(h), c);
  const bool little = scale < 0.0;
  for (long y = 0; y < h; ++y) {
    const uint8_t* row = b.data() + pos + static_cast<uint64_t>(h - 1 - y) * w * c * 4;
    float* out = image.pixel(0, static_cast<int>(y));
    for (long i = 0; i < w * c; ++i) {
      uint8_t q[4];
      std::memcpy(q, row + i * 4, 4);
      if (!little) {
        std::swap(q[0], q[3]);
        std::swap(q[1], q[2]);
      }
      std::memcpy(&out[i], q, 4);
    }
  }
  return image;
}

Result<Image> decodeStb(std::span<const uint8_t> bytes, const std::string& where,
                        const ReadOptions& options) {
  if (bytes.size() > static_cast<size_t>(INT_MAX)) return makeError(where + "file too large");
  const auto* data = bytes.data();
  const int size = static_cast<int>(bytes.size());
  int w = 0, h = 0, c = 0;
  if (!stbi_info_from_memory(data, size, &w, &h, &c)) {
    return makeError(where + "unknown or unsupported image format (" + stbi_failure_reason() + ")");
  }
  PN_TRY(checkSize(w, h, where, options));
  const bool sixteen = stbi_is_16_bit_from_memory(data, size) != 0;
  const bool hasAlpha = c == 2 || c == 4;
  Image image;
  auto fill = [&](auto* pixels, float maxValue, bool table) {
    image = Image(w, h, c);
    std::array<float, 256> lut{};
    for (int i = 0; table && i < 256; ++i) {
      const float v = static_cast<float>(i) / 255.0f;
      lut[i] = options.srgbToLinear ? srgbToLinear(v) : v;
    }
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      const bool isAlpha = hasAlpha && static_cast<int>(i % c) == c - 1;
      const float v = static_cast<float>(pixels[i]) / maxValue;
      if (isAlpha || !options.srgbToLinear) {
        image.pixels[i] = v;
      } else {
        image.pixels[i] = table ? lut[pixels[i] & 0xFF] : srgbToLinear(v);
      }
    }
  };
  if (sixteen) {
    stbi_us* pixels = stbi_load_16_from_memory(data, size, &w, &h, &c, 0);
    if (!pixels) return makeError(where + stbi_failure_reason());
    fill(pixels, 65535.0f, false);
    stbi_image_free(pixels);
  } else {
    stbi_uc* pixels = stbi_load_from_memory(data, size, &w, &h, &c, 0);
    if (!pixels) return makeError(where + stbi_failure_reason());
    fill(pixels, 255.0f, true);
    stbi_image_free(pixels);
  }
  return image;
}

}  // namespace

Result<Image> readImageFromMemory(std::span<const uint8_t> bytes, const std::string& nameForErrors,
                                  const ReadOptions& options) {
  const std::string where = "cannot read '" + nameForErrors + "': ";
  if (bytes.empty()) return makeError(where + "empty file");
  if (startsWith(bytes, {'#', '?'})) {
    auto file = rgbe::decodeFile(bytes, nameForErrors, options.maxPixels, options.maxWidth);
    if (!file) return file.error();  // "cannot read 'NAME': ..." already
    return std::move(file->image);
  }
  if (startsWith(bytes, {0x76, 0x2f, 0x31, 0x01}))
    return detail::readExr(bytes, nameForErrors, options);
  if (startsWith(bytes, {'P', 'F'}) || startsWith(bytes, {'P', 'f'})) {
    return decodePfm(bytes, where, options);
  }
  return decodeStb(bytes, where, options);
}

Result<Image> readImage(const std::string& path, const ReadOptions& options) {
  auto bytes = detail::readFileBytes(path);
  if (!bytes) return bytes.error();
  return readImageFromMemory(*bytes, path, options);
}

}  // namespace penumbra
