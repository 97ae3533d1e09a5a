// libFuzzer target: HDR panorama input.
//  - By default every input goes to Penumbra's own Radiance RGBE codec (rgbe::decodeFile): the
//    route of the packed environment format and of the wasm build, and the only HDR decoder
//    that is Penumbra's code.
//  - With PENUMBRA_FUZZ_DECODERS=1 in the environment, inputs whose first byte is even go to
//    readImageFromMemory instead (every decoder: RGBE, PFM, stb_image, OpenEXR). stb_image and
//    OpenEXR are not instrumented and are fuzzed by their own projects, so that mode is not
//    part of tools/test.
// The first byte is always consumed as the selector, so seeds work in both modes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "image/rgbe.h"
#include "penumbra/ibl.h"
#include "penumbra/image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool decoders = std::getenv("PENUMBRA_FUZZ_DECODERS") != nullptr;
  if (size < 1) return 0;
  const std::span<const uint8_t> bytes(data + 1, size - 1);
  const int64_t maxPixels = int64_t{1} << 22;  // keep RSS under libFuzzer's limit
  if (decoders && (data[0] & 1) == 0) {
    penumbra::ReadOptions options;
    options.maxPixels = maxPixels;
    auto image = penumbra::readImageFromMemory(bytes, "fuzz.hdr", options);
    if (image) (void)penumbra::ibl::radianceVerdict(penumbra::ibl::sanitizeRadiance(*image), "f");
  } else {
    auto decoded = penumbra::rgbe::decodeFile(bytes, "fuzz.hdr", maxPixels);
    // Then the radiance policy every environment goes through (NaN, Inf, overflow).
    if (decoded) {
      (void)penumbra::ibl::radianceVerdict(penumbra::ibl::sanitizeRadiance(decoded->image), "f");
    }
  }
  return 0;
}
