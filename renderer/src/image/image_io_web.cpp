// The wasm build's OpenEXR hooks: neither reading nor writing (no OpenEXR in the browser). All
// other formats decode as natively (image_decode.cpp); PNG and Radiance writing are shared
// (image_common.cpp).
#include "image/image_internal.h"

namespace penumbra::detail {

Result<Image> readExr(std::span<const uint8_t>, const std::string& name, const ReadOptions&) {
  return makeError("cannot read '" + name +
                   "': EXR input is not available in the web build "
                   "(use a packed environment, .hdr or .png)");
}

Status writeExrFile(const std::string&, const std::string& finalPathForErrors, const Image&) {
  return makeError("cannot write '" + finalPathForErrors +
                   "': EXR output is not available in the web build (use .hdr or .png)");
}

}  // namespace penumbra::detail
