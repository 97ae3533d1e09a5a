// GGX split-sum prefilter on the CPU. Per mip, one of two integrators:
//  - filtered importance sampling (Krivanek & Colbert 2008) for the large, sharp mips: every
//    sample reads a smoothed source pyramid at the level whose texels cover the solid angle the
//    sample stands for, so a few hundred samples give a smooth result; the brightest texels
//    (a sun) are split off first and summed exactly (prefilter_direct.cpp), because their
//    glow would otherwise take the shape of the sample set;
//  - direct convolution (prefilter_direct.cpp) for the small, rough mips, where it is exact
//    and cheaper.
// Speed comes from one precomputed sample table per mip (tangent-space directions, weights
// and the density part of the level: no trigonometry per sample), a padded pyramid (bilinear
// taps never cross a face edge, so no seam logic per tap), the per-sample geometry computed
// four samples wide, and threads over texel rows. Every texel is a pure function of its
// inputs, so results do not depend on the thread count.
#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <mutex>

#include "ibl/parallel.h"
#include "ibl/prefilter_internal.h"
#include "ibl/sampling.h"
#include "penumbra/ibl.h"

// std::bit_cast is missing from the libc++ of Debian's Emscripten 3.1.6: a memcpy does the
// same and compiles to a register move.
template <class To, class From>
inline To bitCast(const From& from) {
  static_assert(sizeof(To) == sizeof(From), "bitCast needs equal sizes");
  To to;
  std::memcpy(&to, &from, sizeof(To));
  return to;
}

namespace penumbra::ibl {
namespace {

// Krivanek & Colbert's bias of one level toward blur: it hides the box filter's aliasing.
constexpr float kLodBias = 1.0f;

// At most this many cells of bright excess are summed exactly rather than sampled.
constexpr size_t kMaxBrightCells = 512;


int log2Int(int v) {
  int l = 0;
  while ((1 << (l + 1)) <= v) ++l;
  return l;
}

// One level of the source pyramid: 6 faces of (size + 2)^2 RGB texels (F4, last lane unused),
// the outer ring copied from the neighbouring faces.
struct PaddedLevel {
  int size = 0;
  int stride = 0;
  std::vector<F4> texels;
  F4& at(int face, int px, int py) {
    return texels[(static_cast<size_t>(face) * stride + py) * stride + px];
  }
  const F4& at(int face, int px, int py) const {
    return texels[(static_cast<size_t>(face) * stride + py) * stride + px];
  }
};

// Pads one level: copies the faces and fills the outer ring from the neighbouring faces.
PaddedLevel padLevel(const CubeLevel& faces, int threads) {
  PaddedLevel level;
  const int n = faces[0].width;
  level.size = n;
  level.stride = n + 2;
  level.texels.assign(static_cast<size_t>(kFaceCount) * (n + 2) * (n + 2), F4{});
  parallelFor(kFaceCount, threads, [&](int face) {
    const auto copy = [](F4& dst, const float* src) { dst = F4{src[0], src[1], src[2], 0.0f}; };
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) copy(level.at(face, x + 1, y + 1), faces[face].pixel(x, y));
    }
    // Edge ring: the texel of the neighbouring face nearest to where this face's plane,
    // extended by half a texel, points.
    const auto fromNeighbour = [&](int px, int py) {
      const float s = (static_cast<float>(px - 1) + 0.5f) / static_cast<float>(n);
      const float t = (static_cast<float>(py - 1) + 0.5f) / static_cast<float>(n);
      const CubeCoord c = cubeCoord(cubeDirection(face, s, t));
      const int x = std::clamp(static_cast<int>(c.s * static_cast<float>(n)), 0, n - 1);
      const int y = std::clamp(static_cast<int>(c.t * static_cast<float>(n)), 0, n - 1);
      copy(level.at(face, px, py), faces[c.face].pixel(x, y));
    };
    for (int i = 1; i <= n; ++i) {
      fromNeighbour(0, i);
      fromNeighbour(n + 1, i);
      fromNeighbour(i, 0);
      fromNeighbour(i, n + 1);
    }
    // Corners: where three faces meet, the mean of the three texels around the corner.
    const int corners[4][4] = {
        {0, 0, 1, 1}, {n + 1, 0, n, 1}, {0, n + 1, 1, n}, {n + 1, n + 1, n, n}};
    for (const auto& c : corners) {
      level.at(face, c[0], c[1]) =
          (level.at(face, c[2], c[1]) + level.at(face, c[0], c[3]) + level.at(face, c[2], c[3])) *
          (1.0f / 3.0f);
    }
  });
  return level;
}

// The pyramid the importance sampler reads. Each level is filtered from the padded level
// above with the separable [1 3 3 1] / 8 kernel rather than a 2x2 box: with a box, a small
// bright source smeared over a coarse level keeps that level's square texel shape, and a sun's
// glow in a glossy mip comes out as a pattern of squares; the wider, smoother kernel rounds it.
std::vector<PaddedLevel> buildSamplingPyramid(const CubeLevel& base, int threads) {
  std::vector<PaddedLevel> pyramid;
  pyramid.push_back(padLevel(base, threads));
  for (int n = base[0].width / 2; n >= 1; n /= 2) {
    const PaddedLevel& src = pyramid.back();
    CubeLevel faces;
    parallelFor(kFaceCount, threads, [&](int face) {
      faces[face] = Image(n, n, 3);
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          // Source texels 2x-1 .. 2x+2 are padded columns 2x .. 2x+3.
          F4 sum{};
          static constexpr float kWeights[4] = {1.0f / 8, 3.0f / 8, 3.0f / 8, 1.0f / 8};
          for (int j = 0; j < 4; ++j) {
            F4 row{};
            for (int i = 0; i < 4; ++i) row += src.at(face, 2 * x + i, 2 * y + j) * kWeights[i];
            sum += row * kWeights[j];
          }
          float* p = faces[face].pixel(x, y);
          p[0] = sum[0];
          p[1] = sum[1];
          p[2] = sum[2];
        }
      }
    });
    pyramid.push_back(padLevel(faces, threads));
  }
  return pyramid;
}

// Point i of n of the Fibonacci lattice ((i + 1/2) / n, frac(i / golden ratio)). Hammersley's
// azimuths for a power-of-two n repeat the same few angles ring after ring, and a sun's glow
// in a glossy mip then takes the shape of that pattern (a four-pointed star); the lattice's
// spiral has no such symmetry.
glm::vec2 fibonacciPoint(int i, int n) {
  const double golden = 0.6180339887498949;
  const double frac = static_cast<double>(i) * golden - std::floor(static_cast<double>(i) * golden);
  return {(static_cast<float>(i) + 0.5f) / static_cast<float>(n), static_cast<float>(frac)};
}

// The sample table of one mip, four samples to a lane group (structure of arrays) so the
// per-sample geometry runs four wide. Padding lanes have weight 0.
struct SampleGroup {
  F4 lx, ly, lz;  // l in tangent space, z = n.l > 0
  F4 weight;      // n.l
  F4 lod;         // density part of the level: 0.5 log2(omegaS) + log2(size0 / 2) + bias
};

std::vector<SampleGroup> buildSampleTable(float roughness, int samples, int sourceSize,
                                          float& weightSum) {
  const float alpha = std::max(roughness * roughness, 1e-4f);
  const float texelTerm = std::log2(static_cast<float>(sourceSize) * 0.5f) + kLodBias;
  std::vector<SampleGroup> table;
  double sum = 0.0;
  int lane = 0;
  for (int i = 0; i < samples; ++i) {
    const glm::vec3 h = sampleGgxD(fibonacciPoint(i, samples), alpha);
    const glm::vec3 l(2.0f * h.z * h.x, 2.0f * h.z * h.y, 2.0f * h.z * h.z - 1.0f);
    if (l.z <= 0.0f) continue;
    const float pdf = ggxD(h.z, alpha) * 0.25f;  // D(h) / 4 for v = n
    const float omegaS = 1.0f / (static_cast<float>(samples) * pdf);
    if (lane == 0) table.push_back({F4{0, 0, 0, 0}, F4{0, 0, 0, 0}, F4{1, 1, 1, 1}, F4{}, F4{}});
    SampleGroup& g = table.back();
    g.lx[lane] = l.x;
    g.ly[lane] = l.y;
    g.lz[lane] = l.z;
    g.weight[lane] = l.z;
    g.lod[lane] = 0.5f * std::log2(omegaS) + texelTerm;
    lane = (lane + 1) % 4;
    sum += l.z;
  }
  weightSum = static_cast<float>(sum);
  return table;
}

using I4 = int32_t __attribute__((vector_size(16)));

// The bilinear blend of the 2x2 texels from p (top left) with the given row stride.
inline F4 bilerp(const F4* p0, int stride, float fx, float fy) {
  const F4* p1 = p0 + stride;
  const F4 top = p0[0] + (p0[1] - p0[0]) * fx;
  const F4 bottom = p1[0] + (p1[1] - p1[0]) * fx;
  return top + (bottom - top) * fy;
}

// log2 for positive normal floats, four at a time, within 0.01 (as fastLog2).
inline F4 fastLog2(F4 x) {
  const I4 bits = bitCast<I4>(x);
  const F4 exponent = __builtin_convertvector((bits >> 23) - 127, F4);
  const I4 mantissaBits = (bits & 0x007FFFFF) | 0x3F800000;
  const F4 m = bitCast<F4>(mantissaBits);  // in [1, 2)
  return exponent + (-0.34484843f * m + 2.02466578f) * m - 0.67487759f;
}

inline F4 clampF4(F4 v, float lo, float hi) {
  v = v < lo ? F4{} + lo : v;
  return v > hi ? F4{} + hi : v;
}

// Filtered lookups of the source in four unit directions: face selection as cubeCoord()
// computed four wide (lane selects instead of branches, which would mispredict since
// successive samples point in unrelated directions), then one trilinear fetch per lane.
// The level is each sample's density part plus the texel-size part, which depends on where
// the direction hits its face. Returns the weighted sum of the four values.
inline F4 filteredLookup4(const std::vector<PaddedLevel>& pyramid, F4 dx, F4 dy, F4 dz, F4 lodBase,
                          F4 weight) {
  const I4 signMask = {0x7fffffff, 0x7fffffff, 0x7fffffff, 0x7fffffff};
  const I4 ix = bitCast<I4>(dx) & signMask;
  const I4 iy = bitCast<I4>(dy) & signMask;
  const I4 iz = bitCast<I4>(dz) & signMask;
  const F4 ax = bitCast<F4>(ix);
  const F4 ay = bitCast<F4>(iy);
  const F4 az = bitCast<F4>(iz);
  const I4 xMajor = (ax >= ay) & (ax >= az);
  const I4 yMajor = ~xMajor & (ay >= az);
  const F4 ma = xMajor ? ax : (yMajor ? ay : az);
  const F4 major = xMajor ? dx : (yMajor ? dy : dz);
  const I4 negative = major < 0.0f;
  const I4 face = (xMajor ? I4{} : (yMajor ? I4{} + 2 : I4{} + 4)) + (negative & 1);
  // GL table: +X (-z, -y), -X (z, -y), +Y (x, z), -Y (x, -z), +Z (x, -y), -Z (-x, -y).
  const F4 sc = xMajor ? (negative ? dz : -dz) : (yMajor ? dx : (negative ? -dx : dx));
  const F4 tc = yMajor ? (negative ? -dz : dz) : -dy;
  const F4 inv = 0.5f / ma;
  const F4 s = clampF4(sc * inv + 0.5f, 0.0f, 1.0f);
  const F4 t = clampF4(tc * inv + 0.5f, 0.0f, 1.0f);
  // The source texel's solid angle is (2 / size)^2 ma^3 there, hence -1.5 log2(ma).
  const float maxLod = static_cast<float>(pyramid.size() - 1);
  const F4 lod = clampF4(lodBase - 1.5f * fastLog2(ma), 0.0f, maxLod);
  // Texel addresses of both levels, four wide: level l has size0 / 2^l texels per edge (computed
  // in the same order as one lane at a time would, so the result is bit-identical).
  const I4 l0 = __builtin_convertvector(lod, I4);  // lod >= 0: truncation is floor
  const F4 frac = lod - __builtin_convertvector(l0, F4);
  const F4 sizeA = static_cast<float>(pyramid[0].size) * bitCast<F4>((127 - l0) << 23);
  const F4 sizeB = sizeA * 0.5f;
  const F4 xA = s * sizeA + 0.5f, yA = t * sizeA + 0.5f;  // padded texel space, >= 0.5
  const F4 xB = s * sizeB + 0.5f, yB = t * sizeB + 0.5f;
  const I4 x0A = __builtin_convertvector(xA, I4), y0A = __builtin_convertvector(yA, I4);
  const I4 x0B = __builtin_convertvector(xB, I4), y0B = __builtin_convertvector(yB, I4);
  const F4 fxA = xA - __builtin_convertvector(x0A, F4), fyA = yA - __builtin_convertvector(y0A, F4);
  const F4 fxB = xB - __builtin_convertvector(x0B, F4), fyB = yB - __builtin_convertvector(y0B, F4);
  const I4 strideA = __builtin_convertvector(sizeA, I4) + 2;
  const I4 strideB = __builtin_convertvector(sizeB, I4) + 2;
  const I4 indexA = (face * strideA + y0A) * strideA + x0A;
  const I4 indexB = (face * strideB + y0B) * strideB + x0B;
  F4 sum{};
  for (int i = 0; i < 4; ++i) {
    const PaddedLevel& a = pyramid[l0[i]];
    F4 value = bilerp(a.texels.data() + indexA[i], strideA[i], fxA[i], fyA[i]);
    if (frac[i] > 0.0f) {
      const PaddedLevel& b = pyramid[l0[i] + 1];
      value += (bilerp(b.texels.data() + indexB[i], strideB[i], fxB[i], fyB[i]) - value) * frac[i];
    }
    sum += value * weight[i];
  }
  return sum;
}

Status validate(const PrefilterOptions& options, int faceSize) {
  if (!isPowerOfTwo(faceSize) || faceSize > 16384) {
    return makeError("face size must be a power of two between 1 and 16384, got " +
                     std::to_string(faceSize));
  }
  if (!isPowerOfTwo(options.minFaceSize) || options.minFaceSize > faceSize) {
    return makeError(
        "smallest mip face size must be a power of two no larger than the face size (" +
        std::to_string(faceSize) + "), got " + std::to_string(options.minFaceSize));
  }
  if (options.samples < 1 || options.samples > (1 << 20)) {
    return makeError("sample count must be between 1 and 1048576, got " +
                     std::to_string(options.samples));
  }
  return {};
}

}  // namespace

int importanceSamplesForMip(int samples, int mip) {
  // A rougher lobe spans more output texels, so it needs more samples to look as smooth, and
  // each coarser mip has a quarter of the texels: doubling per mip keeps the cost bounded.
  const int64_t n = static_cast<int64_t>(samples) << std::clamp(mip - 1, 0, 4);
  return static_cast<int>(std::min<int64_t>(n, 1 << 20));
}

int mipCountFor(int faceSize, int minFaceSize) {
  PN_CHECK(isPowerOfTwo(faceSize) && isPowerOfTwo(minFaceSize) && minFaceSize <= faceSize,
           "face sizes must be powers of two with minFaceSize <= faceSize");
  return log2Int(faceSize) - log2Int(minFaceSize) + 1;
}

float roughnessForMip(int mip, int mipCount) {
  if (mipCount <= 1) return 0.0f;
  return static_cast<float>(mip) / static_cast<float>(mipCount - 1);
}

Result<Cubemap> prefilterCubemapCpu(const Cubemap& source, const PrefilterOptions& options) {
  if (source.mipCount() < 1) return makeError("source cube map is empty");
  PN_TRY(validate(options, source.size));
  for (int f = 0; f < kFaceCount; ++f) {
    const Image& face = source.face(0, f);
    if (face.width != source.size || face.height != source.size || face.channels != 3 ||
        face.pixels.size() != static_cast<size_t>(source.size) * source.size * 3) {
      return makeError("source cube face " + std::string(faceName(f)) + " is " +
                       std::to_string(face.width) + "x" + std::to_string(face.height) + " with " +
                       std::to_string(face.channels) + " channels, expected " +
                       std::to_string(source.size) + "x" + std::to_string(source.size) + " RGB");
    }
  }
  const int size = source.size;
  const int mips = mipCountFor(size, options.minFaceSize);
  const std::vector<CubeLevel> plain = boxPyramid(source.mips[0]);

  // Per mip: direct convolution when it fits the budget, filtered importance sampling else.
  std::vector<int> directSource(mips, 0);
  bool anyImportanceSampled = false;
  for (int m = 1; m < mips; ++m) {
    const float r = roughnessForMip(m, mips);
    const int s = directSourceSize(size >> m, std::max(r * r, 1e-4f), size);
    if (directPairs(size >> m, s) <= options.directBudget) {
      directSource[m] = s;
    } else {
      anyImportanceSampled = true;
    }
  }
  // The importance sampler filters a clipped copy; the few texels above the clip are summed
  // exactly instead (see splitBrightTexels).
  std::vector<PaddedLevel> pyramid;
  TexelSet bright;
  if (anyImportanceSampled) {
    CubeLevel clipped;
    // Cells of at most 1/128 of a face edge: a 3-degree sun stays within a few hundred.
    const int cellLevel = std::max(0, log2Int(size) - 7);
    bright = splitBrightTexels(source.mips[0], clipped, kMaxBrightCells, cellLevel);
    pyramid = buildSamplingPyramid(clipped, options.threads);
  }

  Cubemap out(size, mips);
  out.mips[0] = source.mips[0];

  // Progress in output rows, reported at most once per percent.
  int totalRows = 0;
  for (int m = 1; m < mips; ++m) totalRows += kFaceCount * out.faceSize(m);
  std::atomic<int> doneRows{0};
  std::mutex progressMutex;
  int reportedPercent = -1;
  const auto rowDone = [&]() {
    if (!options.progress) return;
    const int done = ++doneRows;
    const int percent = static_cast<int>(100.0 * done / std::max(totalRows, 1));
    std::lock_guard<std::mutex> lock(progressMutex);
    if (percent > reportedPercent) {
      reportedPercent = percent;
      options.progress(static_cast<float>(percent) / 100.0f);
    }
  };

  for (int m = 1; m < mips; ++m) {
    const int n = out.faceSize(m);
    const float roughness = roughnessForMip(m, mips);
    if (directSource[m] > 0) {
      const CubeLevel& src = plain[log2Int(size / directSource[m])];
      convolveDirect(src, std::max(roughness * roughness, 1e-4f), n, out.mips[m], options.threads,
                     rowDone);
      continue;
    }
    float weightSum = 0.0f;
    const std::vector<SampleGroup> table =
        buildSampleTable(roughness, importanceSamplesForMip(options.samples, m), size, weightSum);
    const float norm = weightSum > 0.0f ? 1.0f / weightSum : 0.0f;
    const float alpha = std::max(roughness * roughness, 1e-4f);
    // lobeSum's weights are D (n.l) omega * pi / alpha^2; the integral is normalised by Z.
    const float brightScale =
        static_cast<float>(alpha * alpha / (kPi * ggxLobeNormalization(alpha)));
    parallelFor(kFaceCount * n, options.threads, [&](int row) {
      const int face = row / n;
      const int y = row % n;
      Image& image = out.face(m, face);
      for (int x = 0; x < n; ++x) {
        const glm::vec3 nrm = texelDirection(face, x, y, n);
        // Tangent frame around +Y (glTF up): continuous everywhere but at the two poles.
        glm::vec3 tangent(nrm.z, 0.0f, -nrm.x);
        const float len2 = tangent.x * tangent.x + tangent.z * tangent.z;
        tangent = len2 > 1e-12f ? tangent / std::sqrt(len2) : glm::vec3(1.0f, 0.0f, 0.0f);
        const glm::vec3 bitangent = glm::cross(nrm, tangent);
        F4 acc{};
        for (const SampleGroup& g : table) {
          const F4 dx = tangent.x * g.lx + bitangent.x * g.ly + nrm.x * g.lz;
          const F4 dy = tangent.y * g.lx + bitangent.y * g.ly + nrm.y * g.lz;
          const F4 dz = tangent.z * g.lx + bitangent.z * g.ly + nrm.z * g.lz;
          acc += filteredLookup4(pyramid, dx, dy, dz, g.lod, g.weight);
        }
        acc *= norm;
        if (bright.count > 0) acc += lobeSum(bright, nrm, alpha) * brightScale;
        float* p = image.pixel(x, y);
        for (int k = 0; k < 3; ++k) p[k] = acc[k];
      }
      rowDone();
    });
  }
  if (options.progress) options.progress(1.0f);
  return out;
}

Result<PrefilteredEnvironment> prefilterCpu(const Image& panorama,
                                            const PrefilterOptions& options) {
  PN_TRY(validate(options, options.faceSize));
  // The sun leaves the panorama before filtering: it is drawn as a light of its own.
  Image withoutSun;
  std::optional<Sun> sun;
  if (options.sunThreshold != 0.0f) {
    withoutSun = panorama;
    sun = extractSun(withoutSun, {.threshold = options.sunThreshold});
  }
  auto source = panoramaToCubemap(sun ? withoutSun : panorama, options.faceSize, options.threads);
  if (!source) return source.error();
  auto specular = prefilterCubemapCpu(*source, options);
  if (!specular) return specular.error();
  PrefilteredEnvironment env;
  env.sh = projectSh(*source, 0, options.threads);
  env.specular = std::move(*specular);
  for (int m = 0; m < env.specular.mipCount(); ++m) {
    env.roughness.push_back(roughnessForMip(m, env.specular.mipCount()));
  }
  env.samples = options.samples;
  env.sun = sun;
  env.generator = std::string("penumbra ") + PENUMBRA_VERSION;
  return env;
}

}  // namespace penumbra::ibl
