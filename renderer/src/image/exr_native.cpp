// OpenEXR files through the OpenEXR library itself (natively): reading into float RGB(A) and
// writing half-float, ZIP-compressed files. Going through OpenImageIO for these costs its
// plug-in catalogue on first use (about 0.2 s and 130 MB of a short-lived tool's run).
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <half.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "image/image_internal.h"

namespace penumbra::detail {
namespace {

// A read-only OpenEXR stream over bytes in memory.
class MemoryStream final : public Imf::IStream {
 public:
  explicit MemoryStream(std::span<const uint8_t> bytes) : Imf::IStream("memory"), bytes_(bytes) {}
  bool read(char c[], int n) override {
    if (n < 0 || pos_ + static_cast<uint64_t>(n) > bytes_.size()) {
      throw std::runtime_error("unexpected end of the EXR data");
    }
    std::memcpy(c, bytes_.data() + pos_, static_cast<size_t>(n));
    pos_ += static_cast<uint64_t>(n);
    return pos_ < bytes_.size();
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override {
    if (pos > bytes_.size()) throw std::runtime_error("seek past the end of the EXR data");
    pos_ = pos;
  }

 private:
  std::span<const uint8_t> bytes_;
  uint64_t pos_ = 0;
};

std::string firstLine(const std::string& s) {
  return s.substr(0, s.find('\n'));
}

}  // namespace

Result<Image> readExr(std::span<const uint8_t> bytes, const std::string& name,
                      const ReadOptions& options) {
  const std::string where = "cannot read '" + name + "': ";
  try {
    MemoryStream stream(bytes);
    Imf::InputFile file(stream);
    const Imath::Box2i window = file.header().dataWindow();
    const int64_t w = int64_t{window.max.x} - window.min.x + 1;
    const int64_t h = int64_t{window.max.y} - window.min.y + 1;
    if (w <= 0 || h <= 0) return makeError(where + "empty image");
    if (w * h > options.maxPixels) {
      return makeError(where + "image size " + std::to_string(w) + "x" + std::to_string(h) +
                       " exceeds the limit of " + std::to_string(options.maxPixels) + " pixels");
    }
    // The channels OpenImageIO would give: R, G, B, A as present, in that order (or Y alone).
    const Imf::ChannelList& list = file.header().channels();
    std::vector<const char*> present;
    for (const char* n : {"R", "G", "B", "A"}) {
      if (list.findChannel(n)) present.push_back(n);
    }
    if (present.empty() && list.findChannel("Y")) present.push_back("Y");
    if (present.empty()) return makeError(where + "no R, G, B, A or Y channel");
    const int channels = static_cast<int>(present.size());
    Image image(static_cast<int>(w), static_cast<int>(h), channels);
    const size_t xs = sizeof(float) * static_cast<size_t>(channels);
    const size_t ys = xs * static_cast<size_t>(w);
    // The frame buffer is addressed by absolute data-window coordinates.
    char* base = reinterpret_cast<char*>(image.pixels.data()) -
                 static_cast<std::ptrdiff_t>(window.min.x) * static_cast<std::ptrdiff_t>(xs) -
                 static_cast<std::ptrdiff_t>(window.min.y) * static_cast<std::ptrdiff_t>(ys);
    Imf::FrameBuffer fb;
    for (int c = 0; c < channels; ++c) {
      fb.insert(present[static_cast<size_t>(c)],
                Imf::Slice(Imf::FLOAT, base + static_cast<size_t>(c) * sizeof(float), xs, ys));
    }
    file.setFrameBuffer(fb);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const std::exception& e) {
    return makeError(where + firstLine(e.what()));
  }
}

Status writeExrFile(const std::string& tempPath, const std::string& finalPathForErrors,
                    const Image& image) {
  const std::string where = "cannot write '" + finalPathForErrors + "': ";
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    const char* names[4] = {"R", "G", "B", "A"};
    const int channels = std::clamp(image.channels, 1, 4);
    // OutputFile does not convert pixel types: the half values are made here.
    std::vector<Imath::half> halves(image.pixels.size());
    for (size_t i = 0; i < halves.size(); ++i) halves[i] = Imath::half(image.pixels[i]);
    const size_t xs = sizeof(Imath::half) * static_cast<size_t>(image.channels);
    const size_t ys = xs * static_cast<size_t>(image.width);
    Imf::FrameBuffer fb;
    for (int c = 0; c < channels; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::HALF));
      fb.insert(names[c], Imf::Slice(Imf::HALF,
                                     reinterpret_cast<char*>(halves.data()) +
                                         static_cast<size_t>(c) * sizeof(Imath::half),
                                     xs, ys));
    }
    Imf::OutputFile file(tempPath.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(image.height);
    return {};
  } catch (const std::exception& e) {
    return makeError(where + firstLine(e.what()));
  }
}

}  // namespace penumbra::detail
