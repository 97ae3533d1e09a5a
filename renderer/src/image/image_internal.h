// Internal helpers shared by the native and web image code (image_decode.cpp, exr_native.cpp,
// image_io_web.cpp): atomic
// file writes, whole-file reads, and the per-build hooks that writeImage dispatches to.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/image.h"

namespace penumbra::detail {

// Lower-case extension including the dot (".png"), or "" when there is none.
std::string lowerExtension(const std::string& path);

// Reads a whole file. Errors: "cannot read 'PATH': no such file" and the like.
Result<std::vector<uint8_t>> readFileBytes(const std::string& path);

// Writes a file atomically: `writeTemp` is called with a fresh temporary path in the same
// folder ("PATH.tmp-<pid>-<n>", already created empty so the name is reserved); when it
// succeeds the temporary file is renamed over PATH, otherwise it is removed. Either way no
// half-written file ever appears under PATH.
Status writeAtomic(const std::string& path,
                   const std::function<Status(const std::string& tempPath)>& writeTemp);
// The common case: bytes already in memory.
Status writeFileAtomic(const std::string& path, std::span<const uint8_t> bytes);

// Back-end hooks. The native build reads and writes EXR through OpenEXR; the web build has
// no EXR support and returns an error.
Status writeExrFile(const std::string& tempPath, const std::string& finalPathForErrors,
                    const Image& image);
Result<Image> readExr(std::span<const uint8_t> bytes, const std::string& name,
                      const ReadOptions& options);

// Converts 1..4-channel pixels to the channel count of `image` (helper for encoders).
// Returns RGB floats for pixel i: grey is replicated, alpha ignored.
inline void rgbOf(const Image& image, size_t i, float out[3]) {
  const float* p = &image.pixels[i * image.channels];
  if (image.channels >= 3) {
    out[0] = p[0];
    out[1] = p[1];
    out[2] = p[2];
  } else {
    out[0] = out[1] = out[2] = p[0];
  }
}

}  // namespace penumbra::detail
