// Resampling of 8-bit RGBA pixels (stb_image_resize): texture-array layers of different sizes
// brought to one (gpu/gpu_materials.cpp).
#pragma once

#include <cstdint>
#include <vector>

namespace penumbra {

// `pixels` (w x h RGBA8, rows top first) resampled to nw x nh.
std::vector<uint8_t> resizeRgba8(const std::vector<uint8_t>& pixels, int w, int h, int nw, int nh);

}  // namespace penumbra
