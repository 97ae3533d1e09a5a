// KTX2 (KHR_texture_basisu) textures, one implementation per build: in the browser Binomial's
// Basis Universal transcoder (as three.js packages it on npm), which web/lib/decoders.mjs loads
// only for a file that uses the extension and ktx2_web.cpp calls; natively none (Debian packages
// no transcoder), so the loader takes the texture's fallback image there, with a warning.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "penumbra/scene.h"

namespace penumbra::gltf::backend {

// Whether this build can transcode KTX2 images (loaded for the current file).
bool ktx2Available();

// Transcodes a Basis Universal KTX2 file (layer 0, face 0) into `out`: a block format the GL
// context samples with every level the file has (out.compressedFormat, compressedLevels), or
// else RGBA8 level 0 (pixels), row 0 at the top. Returns an empty string, or the transcoder's
// words for what is wrong. At most `maxPixels` pixels; larger than `maxSize` a side, or
// without `blocks` (an image a texture array's layer takes: gpu/gpu_scene.h), RGBA8.
std::string ktx2Transcode(std::span<const uint8_t> src, uint64_t maxPixels, int maxSize,
                          bool blocks, ImageData& out);

// Whether `bytes` start like a KTX2 file (its 12-byte identifier).
inline bool isKtx2(std::span<const uint8_t> bytes) {
  static constexpr uint8_t kId[12] = {0xAB, 'K',  'T',  'X',  ' ',  '2',
                                      '0',  0xBB, '\r', '\n', 0x1A, '\n'};
  if (bytes.size() < sizeof kId) return false;
  for (size_t i = 0; i < sizeof kId; ++i) {
    if (bytes[i] != kId[i]) return false;
  }
  return true;
}

}  // namespace penumbra::gltf::backend
