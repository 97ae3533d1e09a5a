#include "image/rgbe.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "image/image_internal.h"

namespace penumbra::rgbe {
namespace {

constexpr float kMaxValue = 1e30f;

float sanitize(float v) {
  if (!(v > 0.0f)) return 0.0f;  // also catches NaN
  return v > kMaxValue ? kMaxValue : v;
}

void appendString(std::vector<uint8_t>& out, const std::string& s) {
  out.insert(out.end(), s.begin(), s.end());
  out.push_back('\n');
}

// New-style RLE of one component of a scanline: runs of 4 or more equal bytes become
// (128 + count, value) with count <= 127, everything else literal dumps of at most 128 bytes.
void encodeComponentRle(const uint8_t* data, int n, std::vector<uint8_t>& out) {
  int i = 0;
  while (i < n) {
    int runStart = i;
    int runLength = 0;
    while (runStart < n) {
      runLength = 1;
      while (runStart + runLength < n && runLength < 127 &&
             data[runStart + runLength] == data[runStart]) {
        ++runLength;
      }
      if (runLength >= 4) break;
      runStart += runLength;
      runLength = 0;
    }
    while (i < runStart) {
      const int count = std::min(128, runStart - i);
      out.push_back(static_cast<uint8_t>(count));
      out.insert(out.end(), data + i, data + i + count);
      i += count;
    }
    if (runLength >= 4) {
      out.push_back(static_cast<uint8_t>(128 + runLength));
      out.push_back(data[runStart]);
      i = runStart + runLength;
    }
  }
}

// A forward-only reader over the file bytes with bounds checks.
struct Reader {
  std::span<const uint8_t> bytes;
  size_t pos = 0;

  bool atEnd() const { return pos >= bytes.size(); }
  size_t left() const { return bytes.size() - pos; }
  // Reads one header line without the '\n'. Returns false at the end of the data or when the
  // line is absurdly long (a binary file that is not Radiance).
  bool line(std::string& out) {
    out.clear();
    while (pos < bytes.size()) {
      const char c = static_cast<char>(bytes[pos++]);
      if (c == '\n') return true;
      if (out.size() > (1u << 20)) return false;
      out.push_back(c);
    }
    return false;
  }
};

bool parseInt(const std::string& s, size_t& pos, int& out) {
  while (pos < s.size() && s[pos] == ' ') ++pos;
  int64_t v = 0;
  size_t start = pos;
  while (pos < s.size() && s[pos] >= '0' && s[pos] <= '9') {
    v = v * 10 + (s[pos] - '0');
    if (v > (int64_t{1} << 30)) return false;
    ++pos;
  }
  if (pos == start) return false;
  out = static_cast<int>(v);
  return true;
}

bool expectToken(const std::string& s, size_t& pos, const char* token) {
  while (pos < s.size() && s[pos] == ' ') ++pos;
  const size_t n = std::strlen(token);
  if (s.compare(pos, n, token) != 0) return false;
  pos += n;
  return true;
}

// One scanline of w RGBE pixels into `scan` (new-style RLE, flat, or flat with old-style
// runs); false on truncated or corrupt data.
bool decodeScanline(Reader& in, int w, std::vector<uint8_t>& scan) {
  const std::span<const uint8_t> bytes = in.bytes;
  const bool rle = w >= 8 && w < 32768 && in.left() >= 4 && bytes[in.pos] == 2 &&
                   bytes[in.pos + 1] == 2 && (bytes[in.pos + 2] & 0x80) == 0;
  if (rle) {
    if (((bytes[in.pos + 2] << 8) | bytes[in.pos + 3]) != w) return false;
    in.pos += 4;
    for (int c = 0; c < 4; ++c) {
      int x = 0;
      while (x < w) {
        if (in.atEnd()) return false;
        int count = bytes[in.pos++];
        if (count > 128) {
          count -= 128;
          if (count > w - x || in.atEnd()) return false;
          const uint8_t v = bytes[in.pos++];
          for (int k = 0; k < count; ++k) scan[static_cast<size_t>(x++) * 4 + c] = v;
        } else {
          if (count == 0 || count > w - x || in.left() < static_cast<size_t>(count)) {
            return false;
          }
          for (int k = 0; k < count; ++k)
            scan[static_cast<size_t>(x++) * 4 + c] = bytes[in.pos++];
        }
      }
    }
  } else {
    // Flat quadruples, with old-style runs: (1, 1, 1, n) repeats the previous pixel
    // n << shift times, consecutive run markers shifting by 8 more bits.
    int x = 0;
    int shift = 0;
    while (x < w) {
      if (in.left() < 4) return false;
      const uint8_t* p = &bytes[in.pos];
      in.pos += 4;
      if (p[0] == 1 && p[1] == 1 && p[2] == 1) {
        if (x == 0 || shift > 16) return false;
        const int64_t count = static_cast<int64_t>(p[3]) << shift;
        if (count > w - x) return false;
        for (int64_t k = 0; k < count; ++k, ++x) {
          std::memcpy(&scan[static_cast<size_t>(x) * 4], &scan[static_cast<size_t>(x - 1) * 4],
                      4);
        }
        shift += 8;
      } else {
        std::memcpy(&scan[static_cast<size_t>(x) * 4], p, 4);
        ++x;
        shift = 0;
      }
    }
  }
  return true;
}

}  // namespace

void encodePixel(float r, float g, float b, uint8_t out[4]) {
  r = sanitize(r);
  g = sanitize(g);
  b = sanitize(b);
  const float m = std::max(r, std::max(g, b));
  if (m < 1e-32f) {
    out[0] = out[1] = out[2] = out[3] = 0;
    return;
  }
  int e = 0;
  std::frexp(m, &e);  // m = f * 2^e with f in [0.5, 1)
  float scale = std::ldexp(1.0f, 8 - e);
  // Rounding the largest channel can reach 256: then the exponent goes up by one.
  if (static_cast<int>(m * scale + 0.5f) > 255) {
    ++e;
    scale *= 0.5f;
  }
  out[0] = static_cast<uint8_t>(std::min(255, static_cast<int>(r * scale + 0.5f)));
  out[1] = static_cast<uint8_t>(std::min(255, static_cast<int>(g * scale + 0.5f)));
  out[2] = static_cast<uint8_t>(std::min(255, static_cast<int>(b * scale + 0.5f)));
  out[3] = static_cast<uint8_t>(e + 128);
}

void decodePixel(const uint8_t in[4], float out[3]) {
  if (in[3] == 0) {
    out[0] = out[1] = out[2] = 0.0f;
    return;
  }
  const float f = std::ldexp(1.0f, static_cast<int>(in[3]) - 136);
  out[0] = static_cast<float>(in[0]) * f;
  out[1] = static_cast<float>(in[1]) * f;
  out[2] = static_cast<float>(in[2]) * f;
}

std::vector<uint8_t> encodeFile(const Image& image, std::span<const std::string> headerLines) {
  PN_CHECK(image.channels >= 1 && image.channels <= 4, "image must have 1 to 4 channels");
  const int w = image.width;
  const int h = image.height;
  std::vector<uint8_t> out;
  out.reserve(static_cast<size_t>(w) * h * 2 + 1024);
  appendString(out, "#?RADIANCE");
  for (const std::string& line : headerLines) {
    PN_CHECK(line.find('\n') == std::string::npos, "header lines must not contain newlines");
    // Readers derived from Walter's rgbe.c (OpenImageIO among them) read the header in 127- or
    // 128-byte chunks; a line whose length is a multiple of that leaves a chunk holding only
    // "\n", which they take for the blank line that ends the header. Trailing spaces avoid it.
    std::string padded = line;
    while (padded.size() >= 127 && (padded.size() % 127 == 0 || padded.size() % 128 == 0)) {
      padded.push_back(' ');
    }
    appendString(out, padded);
  }
  appendString(out, "FORMAT=32-bit_rle_rgbe");
  appendString(out, "");
  appendString(out, "-Y " + std::to_string(h) + " +X " + std::to_string(w));

  const bool rle = w >= 8 && w < 32768;
  std::vector<uint8_t> scan(static_cast<size_t>(w) * 4);
  std::vector<uint8_t> component(static_cast<size_t>(w));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float rgb[3];
      detail::rgbOf(image, static_cast<size_t>(y) * w + x, rgb);
      encodePixel(rgb[0], rgb[1], rgb[2], &scan[static_cast<size_t>(x) * 4]);
    }
    if (!rle) {
      out.insert(out.end(), scan.begin(), scan.end());
      continue;
    }
    out.push_back(2);
    out.push_back(2);
    out.push_back(static_cast<uint8_t>(w >> 8));
    out.push_back(static_cast<uint8_t>(w & 0xff));
    for (int c = 0; c < 4; ++c) {
      for (int x = 0; x < w; ++x) component[x] = scan[static_cast<size_t>(x) * 4 + c];
      encodeComponentRle(component.data(), w, out);
    }
  }
  return out;
}

Result<Decoder> Decoder::start(std::vector<uint8_t> bytes, const std::string& nameForErrors,
                               int64_t maxPixels, int maxWidth) {
  Decoder d;
  d.bytes_ = std::move(bytes);
  d.where_ = "'" + nameForErrors + "'";
  const std::string& where = d.where_;
  Reader in{d.bytes_};
  std::string line;
  if (!in.line(line) || line.size() < 2 || line[0] != '#' || line[1] != '?') {
    return makeError("cannot read " + where + ": not a Radiance RGBE (.hdr) file");
  }
  for (;;) {
    if (!in.line(line)) return makeError("cannot read " + where + ": truncated Radiance header");
    if (line.empty()) break;
    if (line.rfind("FORMAT=", 0) == 0 && line != "FORMAT=32-bit_rle_rgbe") {
      return makeError("cannot read " + where + ": unsupported Radiance format '" + line.substr(7) +
                       "' (only 32-bit_rle_rgbe)");
    }
    d.result_.headerLines.push_back(line);
  }
  if (!in.line(line)) return makeError("cannot read " + where + ": missing resolution line");
  size_t pos = 0;
  int w = 0;
  int h = 0;
  if (!expectToken(line, pos, "-Y") || !parseInt(line, pos, h) || !expectToken(line, pos, "+X") ||
      !parseInt(line, pos, w)) {
    return makeError("cannot read " + where + ": unsupported resolution line '" +
                     line.substr(0, 40) + "' (only '-Y H +X W')");
  }
  if (w <= 0 || h <= 0) {
    return makeError("cannot read " + where + ": image size " + std::to_string(w) + "x" +
                     std::to_string(h) + " is out of range");
  }
  if (static_cast<int64_t>(w) * h > maxPixels) {
    return makeError("cannot read " + where + ": " + std::to_string(w) + "x" + std::to_string(h) +
                     " pixels is more than the " + std::to_string(maxPixels / 1000000) +
                     " million allowed");
  }
  // Even fully run-length encoded data needs 2 bytes per 127 pixels and component; refusing
  // files far too short for their size keeps a forged header from allocating gigabytes.
  if (static_cast<int64_t>(in.left()) * 127 < static_cast<int64_t>(w) * h) {
    return makeError("cannot read " + where + ": truncated RGBE data");
  }
  d.pos_ = in.pos;
  d.width_ = w;
  d.height_ = h;
  // The box filter's factor and the decoded size.
  d.shrink_ = maxWidth > 0 && w > maxWidth ? (w + maxWidth - 1) / maxWidth : 1;
  d.result_.image = Image(std::max(1, w / d.shrink_), std::max(1, h / d.shrink_), 3, 0.0f);
  d.scan_.resize(static_cast<size_t>(w) * 4);
  return d;
}

Status Decoder::step(int rows) {
  Reader in{bytes_, pos_};
  const int w = width_, k = shrink_;
  Image& image = result_.image;
  const int ow = image.width, oh = image.height;
  for (int end = std::min(height_, row_ + std::max(rows, 1)); row_ < end; ++row_) {
    if (!decodeScanline(in, w, scan_)) {
      return makeError("cannot read " + where_ + ": truncated or corrupt RGBE data at scanline " +
                       std::to_string(row_));
    }
    if (k == 1) {
      float* row = image.pixel(0, row_);
      for (int x = 0; x < w; ++x) decodePixel(&scan_[static_cast<size_t>(x) * 4], row + x * 3);
      continue;
    }
    float* row = image.pixel(0, std::min(row_ / k, oh - 1));
    for (int x = 0; x < w; ++x) {
      float v[3];
      decodePixel(&scan_[static_cast<size_t>(x) * 4], v);
      float* o = row + std::min(x / k, ow - 1) * 3;
      o[0] += v[0];
      o[1] += v[1];
      o[2] += v[2];
    }
  }
  pos_ = in.pos;
  return {};
}

DecodedFile Decoder::finish() {
  PN_CHECK(done(), "rgbe::Decoder::finish before every row was decoded");
  Image& image = result_.image;
  if (shrink_ > 1) {
    // Sums to means: square blocks, the last ones wider or taller by the remainder.
    for (int oy = 0; oy < image.height; ++oy) {
      const int rows = oy == image.height - 1 ? height_ - oy * shrink_ : shrink_;
      for (int ox = 0; ox < image.width; ++ox) {
        const int cols = ox == image.width - 1 ? width_ - ox * shrink_ : shrink_;
        const float inv = 1.0f / static_cast<float>(rows * cols);
        float* o = image.pixel(ox, oy);
        o[0] *= inv;
        o[1] *= inv;
        o[2] *= inv;
      }
    }
  }
  bytes_.clear();
  return std::move(result_);
}

Result<DecodedFile> decodeFile(std::span<const uint8_t> bytes, const std::string& nameForErrors,
                               int64_t maxPixels, int maxWidth) {
  auto d = Decoder::start(std::vector<uint8_t>(bytes.begin(), bytes.end()), nameForErrors,
                          maxPixels, maxWidth);
  if (!d) return d.error();
  PN_TRY(d->step(d->height()));
  return d->finish();
}

}  // namespace penumbra::rgbe
