// Native image reading through OpenImageIO (any format it knows) and EXR writing (half
// float). PNG and Radiance writing are shared with the web build (image_common.cpp).
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <array>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>

#include "image/image_internal.h"
#include "penumbra/image.h"

namespace penumbra {
namespace {

namespace OIIO = OIIO_NAMESPACE;

// OIIO picks a reader by file extension; memory buffers have none, so sniff the magic bytes.
std::string extensionFromMagic(std::span<const uint8_t> b) {
  const auto starts = [&](std::initializer_list<uint8_t> magic) {
    if (b.size() < magic.size()) return false;
    return std::equal(magic.begin(), magic.end(), b.begin());
  };
  if (starts({0x89, 'P', 'N', 'G'})) return ".png";
  if (starts({0x76, 0x2f, 0x31, 0x01})) return ".exr";
  if (starts({'#', '?'})) return ".hdr";
  if (starts({0xff, 0xd8, 0xff})) return ".jpg";
  if (starts({'B', 'M'})) return ".bmp";
  if (starts({'I', 'I', 42, 0}) || starts({'M', 'M', 0, 42})) return ".tif";
  return "";
}

// sRGB decoding of normalised integer data, through a table for the common 8-bit case.
void decodeSrgb(Image& image, int alphaChannel, bool eightBit) {
  std::array<float, 256> table{};
  for (int i = 0; i < 256; ++i) table[i] = srgbToLinear(static_cast<float>(i) / 255.0f);
  const int c = image.channels;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    if (static_cast<int>(i % c) == alphaChannel) continue;
    float& v = image.pixels[i];
    if (eightBit) {
      const int index = static_cast<int>(v * 255.0f + 0.5f);
      v = table[std::clamp(index, 0, 255)];
    } else {
      v = srgbToLinear(v);
    }
  }
}

Result<Image> readWith(OIIO::ImageInput* input, const std::string& name,
                       const ReadOptions& options) {
  const OIIO::ImageSpec& spec = input->spec();
  const int64_t pixels = static_cast<int64_t>(spec.width) * spec.height;
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    return makeError("cannot read '" + name + "': empty image");
  }
  if (pixels > options.maxPixels || spec.depth > 1) {
    return makeError("cannot read '" + name + "': image size " + std::to_string(spec.width) + "x" +
                     std::to_string(spec.height) + " exceeds the limit of " +
                     std::to_string(options.maxPixels) + " pixels");
  }
  const int channels = std::min(spec.nchannels, 4);
  Image image(spec.width, spec.height, channels);
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, image.pixels.data())) {
    std::string err = input->geterror();
    if (err.empty()) err = "decoding failed";
    return makeError("cannot read '" + name + "': " + err.substr(0, err.find('\n')));
  }
  const OIIO::TypeDesc::BASETYPE base = static_cast<OIIO::TypeDesc::BASETYPE>(spec.format.basetype);
  const bool integer = base == OIIO::TypeDesc::UINT8 || base == OIIO::TypeDesc::UINT16 ||
                       base == OIIO::TypeDesc::INT8 || base == OIIO::TypeDesc::INT16;
  if (integer && options.srgbToLinear) {
    decodeSrgb(image, spec.alpha_channel, base == OIIO::TypeDesc::UINT8);
  }
  return image;
}

// PNG alpha is unassociated; without this hint OpenImageIO premultiplies colour by alpha on
// read, so a round trip would not return the stored values.
const OIIO::ImageSpec& readConfig() {
  static const OIIO::ImageSpec config = [] {
    OIIO::ImageSpec spec;
    spec.attribute("oiio:UnassociatedAlpha", 1);
    return spec;
  }();
  return config;
}

std::string oiioError() {
  std::string err = OIIO::geterror();
  if (err.empty()) return "unknown or unsupported image format";
  return err.substr(0, err.find('\n'));
}

}  // namespace

Result<Image> readImage(const std::string& path, const ReadOptions& options) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    return makeError("cannot read '" + path + "': no such file");
  }
  if (std::filesystem::is_directory(path, ec)) {
    return makeError("cannot read '" + path + "': it is a folder");
  }
  try {
    auto input = OIIO::ImageInput::open(path, &readConfig());
    if (!input) return makeError("cannot read '" + path + "': " + oiioError());
    return readWith(input.get(), path, options);
  } catch (const std::exception& e) {
    return makeError("cannot read '" + path + "': " + e.what());
  }
}

Result<Image> readImageFromMemory(std::span<const uint8_t> bytes, const std::string& nameForErrors,
                                  const ReadOptions& options) {
  const std::string ext = extensionFromMagic(bytes);
  if (ext.empty()) {
    return makeError("cannot read '" + nameForErrors + "': unknown or unsupported image format");
  }
  try {
    OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
    // With a config, OpenImageIO 2.4 takes the proxy from the config's "oiio:ioproxy".
    OIIO::ImageSpec config = readConfig();
    OIIO::Filesystem::IOProxy* proxy = &memory;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    auto input = OIIO::ImageInput::open("memory" + ext, &config, &memory);
    if (!input) return makeError("cannot read '" + nameForErrors + "': " + oiioError());
    return readWith(input.get(), nameForErrors, options);
  } catch (const std::exception& e) {
    return makeError("cannot read '" + nameForErrors + "': " + e.what());
  }
}

namespace detail {

Status writeExrFile(const std::string& tempPath, const std::string& finalPathForErrors,
                    const Image& image) {
  const std::string where = "cannot write '" + finalPathForErrors + "': ";
  try {
    // Created by format name: the temporary file's name does not end in .exr.
    auto output = OIIO::ImageOutput::create("openexr");
    if (!output) return makeError(where + oiioError());
    OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::HALF);
    spec.attribute("compression", "zip");
    if (!output->open(tempPath, spec)) return makeError(where + output->geterror());
    const bool ok = output->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
    std::string err = ok ? "" : output->geterror();
    if (!output->close() && ok) err = output->geterror();
    if (!err.empty()) return makeError(where + err.substr(0, err.find('\n')));
    return {};
  } catch (const std::exception& e) {
    return makeError(where + e.what());
  }
}

}  // namespace detail
}  // namespace penumbra
