// MemoryCharge: the bytes one texture, renderbuffer or buffer holds, counted while it lives, so
// that the GPU memory Penumbra's objects take can be reported (liveBytes()) and kept in check on
// phones. Move-only, like the Handle it sits beside.
#pragma once

#include <cstdint>

namespace penumbra::gl {

class MemoryCharge {
 public:
  MemoryCharge() = default;
  explicit MemoryCharge(int64_t bytes);
  ~MemoryCharge();
  MemoryCharge(MemoryCharge&& other) noexcept;
  MemoryCharge& operator=(MemoryCharge&& other) noexcept;
  MemoryCharge(const MemoryCharge&) = delete;
  MemoryCharge& operator=(const MemoryCharge&) = delete;

  int64_t bytes() const { return bytes_; }

 private:
  int64_t bytes_ = 0;
};

// The bytes of every live charge in this process: the sizes and formats asked for, mip levels
// and layers included (what a driver pads, or a browser keeps beside, is not counted).
int64_t liveBytes();

// Bytes of `levels` mip levels from width x height at `bytesPerTexel`, times `layers`.
int64_t storageBytes(int width, int height, int levels, int bytesPerTexel, int layers = 1);

}  // namespace penumbra::gl
