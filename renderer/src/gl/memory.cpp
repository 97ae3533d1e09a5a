#include "gl/memory.h"

#include <algorithm>
#include <atomic>
#include <utility>

namespace penumbra::gl {
namespace {

std::atomic<int64_t>& counter() {
  static std::atomic<int64_t> bytes{0};
  return bytes;
}

}  // namespace

MemoryCharge::MemoryCharge(int64_t bytes) : bytes_(bytes) {
  counter() += bytes_;
}
MemoryCharge::~MemoryCharge() {
  counter() -= bytes_;
}
MemoryCharge::MemoryCharge(MemoryCharge&& other) noexcept
    : bytes_(std::exchange(other.bytes_, 0)) {}
MemoryCharge& MemoryCharge::operator=(MemoryCharge&& other) noexcept {
  if (this != &other) {
    counter() -= bytes_;
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

int64_t liveBytes() {
  return counter().load();
}

int64_t storageBytes(int width, int height, int levels, int bytesPerTexel, int layers) {
  int64_t texels = 0;
  for (int l = 0; l < levels; ++l) {
    texels += int64_t{std::max(1, width >> l)} * std::max(1, height >> l);
  }
  return texels * bytesPerTexel * layers;
}

}  // namespace penumbra::gl
