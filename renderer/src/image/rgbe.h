// Radiance RGBE (.hdr) codec written for Penumbra rather than taken from a library, so that
// the packed environment format (docs/environment-format.md) reads identically natively and in
// wasm, and so that write -> read -> write is bit-exact.
//
// Pixel encoding: the largest of R, G, B is written as m * 2^e with mantissa m in [128, 255];
// each channel c is stored as round(c * 2^(8 - e)) and the exponent byte as e + 128.
// Decoding is c = byte * 2^(E - 136) for E != 0 and 0 for E == 0, exactly what stb_image and
// OpenImageIO (Walter's rgbe.c) do, so every reader sees the same floats. Decoded values are
// fixed points of the encoder: encode(decode(p)) == p for every pixel the encoder produces.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/image.h"

namespace penumbra::rgbe {

// NaN and negative values become 0, +Inf and values beyond 1e30 become 1e30.
void encodePixel(float r, float g, float b, uint8_t out[4]);
void decodePixel(const uint8_t in[4], float out[3]);

// A whole file: "#?RADIANCE", then `headerLines` (each one line without '\n', e.g.
// "KEY=value"), "FORMAT=32-bit_rle_rgbe", a blank line, "-Y H +X W", then the scanlines from
// the top row down. Scanlines use the new-style run-length encoding when 8 <= W < 32768 (as
// every Radiance reader expects), flat RGBE quadruples otherwise. Grey images are replicated to
// RGB; alpha is dropped. A header line of 127 bytes or more whose length is a multiple of 127
// or 128 gets trailing spaces (see rgbe.cpp: chunked header readers would end the header early).
std::vector<uint8_t> encodeFile(const Image& image, std::span<const std::string> headerLines = {});

struct DecodedFile {
  Image image;                           // 3 channels, row 0 = top
  std::vector<std::string> headerLines;  // every header line after the "#?" line, in order
};
// Reads flat, new-style RLE and old-style RLE scanlines. Only the standard "-Y H +X W"
// orientation is accepted. Errors name `nameForErrors`. With maxWidth > 0, an image wider than
// that is box-filtered while it decodes, by the smallest integer factor k that brings its width
// to at most maxWidth: (W / k) x (H / k) pixels, the last column and row of blocks taking the
// remainder; no full-size image is ever held (an 8192x4096 panorama is 400 MB as floats).
Result<DecodedFile> decodeFile(std::span<const uint8_t> bytes, const std::string& nameForErrors,
                               int64_t maxPixels = int64_t{1} << 28, int maxWidth = 0);

// The same decoding in steps: start() reads the header (and refuses what decodeFile refuses),
// each step() decodes some scanlines, finish() returns the image. A caller on a UI thread (the
// browser viewer) yields between steps, so a large panorama never blocks it for long.
class Decoder {
 public:
  static Result<Decoder> start(std::vector<uint8_t> bytes, const std::string& nameForErrors,
                               int64_t maxPixels = int64_t{1} << 28, int maxWidth = 0);
  int width() const { return width_; }    // the file's
  int height() const { return height_; }
  bool done() const { return row_ >= height_; }
  // Decodes up to `rows` more scanlines (at least one); an error names the file and scanline.
  Status step(int rows);
  // After done(): the image (box-filtered with maxWidth) and the header lines.
  DecodedFile finish();

 private:
  std::vector<uint8_t> bytes_;
  std::string where_;
  size_t pos_ = 0;
  int width_ = 0, height_ = 0, row_ = 0, shrink_ = 1;
  std::vector<uint8_t> scan_;
  DecodedFile result_;
};

}  // namespace penumbra::rgbe
