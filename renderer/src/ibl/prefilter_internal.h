// Internal pieces of the CPU prefilter shared between its two integrators: filtered importance
// sampling (prefilter.cpp) for sharp lobes on large mips, and direct convolution
// (prefilter_direct.cpp) for rough lobes on small mips, where it is both exact and cheap.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "penumbra/ibl.h"

namespace penumbra::ibl {

using CubeLevel = std::array<Image, kFaceCount>;

// Four floats processed as one SIMD value (GCC/Clang vector extension: SSE natively, wasm
// SIMD128 when enabled, scalar code otherwise). Explicit lanes keep float sums in a fixed
// order, so results are deterministic without -ffast-math.
using F4 = float __attribute__((vector_size(16)));

// 2x2 box-filtered levels of `base` (a power-of-two face size) down to 1x1; [0] is `base`.
std::vector<CubeLevel> boxPyramid(const CubeLevel& base);

// Face size of the source level a direct convolution of a lobe with GGX `alpha` into faces of
// `outSize` reads: at least outSize, 16, and 4 / alpha (a quarter of the lobe's width per
// texel), at most `sourceSize`; a power of two.
int directSourceSize(int outSize, float alpha, int sourceSize);

// Number of (output texel, source texel) pairs of that convolution.
inline int64_t directPairs(int outSize, int sourceLevelSize) {
  const int64_t a = int64_t{kFaceCount} * outSize * outSize;
  const int64_t b = int64_t{kFaceCount} * sourceLevelSize * sourceLevelSize;
  return a * b;
}

// Source texels as a structure of arrays, four to a lane group, for the exact lobe sums.
// Padding lanes have omega = 0 and contribute nothing.
struct TexelSet {
  std::vector<F4> dx, dy, dz, omega, r, g, b;
  size_t count = 0;
  void add(const glm::vec3& direction, float solidAngle, const float rgb[3]);
};
// Every texel of a level.
TexelSet texelsOf(const CubeLevel& level);

// Sum over the set of w_i L_i (lanes 0..2) and of w_i (lane 3) for the GGX lobe around n,
// with w_i = D(h_i) (n.l_i)+ omega_i * pi / alpha^2 and h_i = normalize(n + l_i).
F4 lobeSum(const TexelSet& texels, const glm::vec3& n, float alpha);

// Z(alpha) = integral over the sphere of D(h) (n.l)+ dl with h = normalize(n + l): the
// normaliser of the prefiltered integral (4 as alpha -> 0, 1 at alpha = 1).
double ggxLobeNormalization(float alpha);

// out[f] (outSize^2, RGB) = per texel direction n, the exact sum over every source texel i of
// L_i D(h_i) (n.l_i)+ omega_i / sum D(h_i) (n.l_i)+ omega_i, h_i = normalize(n + l_i).
// `rowDone` is called after each output row.
void convolveDirect(const CubeLevel& source, float alpha, int outSize, CubeLevel& out, int threads,
                    const std::function<void()>& rowDone);

// Splits `base` into a clipped copy and the bright excess, for the importance sampler: every
// texel brighter than the clip is scaled down to it (hue kept), and the excess is summed per
// cell of (2^cellLevel)^2 texels into one entry at the cell's energy-weighted centroid. The
// clip is 8 x the mean luminance, raised until at most maxBright cells hold excess. The sampler
// filters the clipped map, and the bright excess (a sun) is summed exactly per output texel:
// its glow is then smooth at any sample count instead of taking the shape of the sample set.
TexelSet splitBrightTexels(const CubeLevel& base, CubeLevel& clipped, size_t maxBright,
                           int cellLevel);

}  // namespace penumbra::ibl
