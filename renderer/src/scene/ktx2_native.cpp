// Native builds have no Basis Universal transcoder (ktx2_backend.h).
#include "scene/ktx2_backend.h"

namespace penumbra::gltf::backend {

bool ktx2Available() {
  return false;
}

std::string ktx2Transcode(std::span<const uint8_t>, uint64_t, int, bool, ImageData&) {
  return "no KTX2 transcoder in this build";
}

}  // namespace penumbra::gltf::backend
