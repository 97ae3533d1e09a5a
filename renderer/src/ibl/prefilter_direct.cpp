// Direct GGX convolution for the rough mips. Filtered importance sampling has to read very
// coarse pyramid levels for wide lobes, and those levels snap a small bright source to their
// texel grid (up to half a coarse texel off), which shows as tens of percent of error next to a
// sun. A wide lobe needs only a coarse source, and the output is small, so summing over every
// source texel costs little: with 256-pixel input it handles the mips from 32 pixels down in a
// few tens of milliseconds.
#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>

#include <glm/geometric.hpp>

#include "ibl/parallel.h"
#include "ibl/prefilter_internal.h"

namespace penumbra::ibl {

std::vector<CubeLevel> boxPyramid(const CubeLevel& base) {
  std::vector<CubeLevel> levels{base};
  for (int n = base[0].width / 2; n >= 1; n /= 2) {
    const CubeLevel& src = levels.back();
    CubeLevel dst;
    for (int f = 0; f < kFaceCount; ++f) {
      dst[f] = Image(n, n, 3);
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          const float* a = src[f].pixel(2 * x, 2 * y);
          const float* b = src[f].pixel(2 * x + 1, 2 * y);
          const float* c = src[f].pixel(2 * x, 2 * y + 1);
          const float* d = src[f].pixel(2 * x + 1, 2 * y + 1);
          float* o = dst[f].pixel(x, y);
          for (int k = 0; k < 3; ++k) o[k] = 0.25f * (a[k] + b[k] + c[k] + d[k]);
        }
      }
    }
    levels.push_back(std::move(dst));
  }
  return levels;
}

int directSourceSize(int outSize, float alpha, int sourceSize) {
  const float wanted = std::max({static_cast<float>(outSize), 16.0f, 4.0f / alpha});
  int size = 1;
  while (static_cast<float>(size) < wanted && size < sourceSize) size *= 2;
  return std::min(size, sourceSize);
}

void TexelSet::add(const glm::vec3& direction, float solidAngle, const float rgb[3]) {
  const size_t group = count / 4;
  const int lane = static_cast<int>(count % 4);
  if (lane == 0) {
    for (auto* v : {&dx, &dy, &dz, &omega, &r, &g, &b}) v->push_back(F4{});
  }
  dx[group][lane] = direction.x;
  dy[group][lane] = direction.y;
  dz[group][lane] = direction.z;
  omega[group][lane] = solidAngle;
  r[group][lane] = rgb[0];
  g[group][lane] = rgb[1];
  b[group][lane] = rgb[2];
  ++count;
}

TexelSet texelsOf(const CubeLevel& level) {
  TexelSet set;
  const int s = level[0].width;
  const std::vector<double> omega = texelSolidAngles(s);
  for (int f = 0; f < kFaceCount; ++f) {
    for (int y = 0; y < s; ++y) {
      for (int x = 0; x < s; ++x) {
        set.add(texelDirection(f, x, y, s),
                static_cast<float>(omega[static_cast<size_t>(y) * s + x]), level[f].pixel(x, y));
      }
    }
  }
  return set;
}

F4 lobeSum(const TexelSet& texels, const glm::vec3& n, float alpha) {
  const float a2m1 = alpha * alpha - 1.0f;
  F4 sr{}, sg{}, sb{}, sw{};
  const size_t groups = texels.dx.size();
  for (size_t k = 0; k < groups; ++k) {
    // With h = normalize(n + l): (n.h)^2 = (1 + n.l) / 2, so D needs only c = n.l.
    F4 c = n.x * texels.dx[k] + n.y * texels.dy[k] + n.z * texels.dz[k];
    c = c > 0.0f ? c : F4{};
    const F4 d = (0.5f + 0.5f * c) * a2m1 + 1.0f;
    const F4 w = c * texels.omega[k] / (d * d);
    sr += w * texels.r[k];
    sg += w * texels.g[k];
    sb += w * texels.b[k];
    sw += w;
  }
  // Lanes added in a fixed order: deterministic without -ffast-math.
  const auto total = [](const F4& v) { return (v[0] + v[1]) + (v[2] + v[3]); };
  return F4{total(sr), total(sg), total(sb), total(sw)};
}

double ggxLobeNormalization(float alpha) {
  // In t = (n.h)^2 (n.l = 2t - 1, d omega_l = 4 (n.h) d omega_h):
  //   Z = 4 alpha^2 integral_{1/2}^{1} (2t - 1) / (1 + (alpha^2 - 1) t)^2 dt,
  // with t = 1 - x^2 / 2 to resolve the peak at t = 1 for small alpha.
  const double a2 = static_cast<double>(alpha) * alpha;
  constexpr int kSteps = 1 << 16;
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double x = (i + 0.5) / kSteps;
    const double t = 1.0 - 0.5 * x * x;
    const double d = 1.0 + (a2 - 1.0) * t;
    sum += (2.0 * t - 1.0) / (d * d) * x;  // dt = x dx
  }
  return 4.0 * a2 * sum / kSteps;
}

void convolveDirect(const CubeLevel& source, float alpha, int outSize, CubeLevel& out, int threads,
                    const std::function<void()>& rowDone) {
  const TexelSet texels = texelsOf(source);
  for (Image& face : out) face = Image(outSize, outSize, 3);
  parallelFor(kFaceCount * outSize, threads, [&](int row) {
    const int face = row / outSize;
    const int y = row % outSize;
    for (int x = 0; x < outSize; ++x) {
      const F4 sum = lobeSum(texels, texelDirection(face, x, y, outSize), alpha);
      const float inv = sum[3] > 0.0f ? 1.0f / sum[3] : 0.0f;
      float* p = out[face].pixel(x, y);
      p[0] = sum[0] * inv;
      p[1] = sum[1] * inv;
      p[2] = sum[2] * inv;
    }
    if (rowDone) rowDone();
  });
}

TexelSet splitBrightTexels(const CubeLevel& base, CubeLevel& clipped, size_t maxBright,
                           int cellLevel) {
  const int s = base[0].width;
  const int cellSize = std::max(1, s >> cellLevel);  // cells per face edge
  const int shift = std::countr_zero(static_cast<unsigned>(s / cellSize));
  const auto luminance = [](const float* p) {
    return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
  };
  const auto cellOf = [&](int f, int x, int y) {
    return (static_cast<size_t>(f) * cellSize + (y >> shift)) * cellSize + (x >> shift);
  };
  // The clip: 8 x the mean luminance, raised until at most maxBright cells exceed it.
  std::vector<float> cellMax(static_cast<size_t>(kFaceCount) * cellSize * cellSize, 0.0f);
  double weighted = 0.0;
  const std::vector<double> omegas = texelSolidAngles(s);
  for (int f = 0; f < kFaceCount; ++f) {
    for (int y = 0; y < s; ++y) {
      for (int x = 0; x < s; ++x) {
        const float l = luminance(base[f].pixel(x, y));
        weighted += l * omegas[static_cast<size_t>(y) * s + x];
        float& m = cellMax[cellOf(f, x, y)];
        m = std::max(m, l);
      }
    }
  }
  float clip = static_cast<float>(8.0 * weighted / (4.0 * 3.14159265358979323846));
  if (maxBright < cellMax.size()) {
    std::nth_element(cellMax.begin(), cellMax.begin() + static_cast<std::ptrdiff_t>(maxBright),
                     cellMax.end(), std::greater<float>());
    clip = std::max(clip, cellMax[maxBright]);
  }
  // Scale texels above the clip down to it (hue kept) and gather the excess per cell:
  // excess radiance times solid angle, at the cell's energy-weighted centroid direction.
  struct Cell {
    glm::dvec3 energy{0.0};    // sum of excess * omega, RGB
    glm::dvec3 centroid{0.0};  // sum of direction * luminance * omega
    double omega = 0.0;
  };
  std::vector<Cell> cells(static_cast<size_t>(kFaceCount) * cellSize * cellSize);
  clipped = base;
  for (int f = 0; f < kFaceCount; ++f) {
    for (int y = 0; y < s; ++y) {
      for (int x = 0; x < s; ++x) {
        float* p = clipped[f].pixel(x, y);
        const float l = luminance(p);
        if (!(l > clip)) continue;
        const float keep = clip / l;
        const double omega = omegas[static_cast<size_t>(y) * s + x];
        Cell& c = cells[cellOf(f, x, y)];
        const glm::dvec3 excess(p[0] * (1.0f - keep), p[1] * (1.0f - keep), p[2] * (1.0f - keep));
        c.energy += excess * omega;
        c.centroid += glm::dvec3(texelDirection(f, x, y, s)) * ((l - clip) * omega);
        c.omega += omega;
        for (int k = 0; k < 3; ++k) p[k] *= keep;
      }
    }
  }
  TexelSet bright;
  for (const Cell& c : cells) {
    if (c.omega <= 0.0) continue;
    const glm::dvec3 radiance = c.energy / c.omega;
    const float rgb[3] = {static_cast<float>(radiance.x), static_cast<float>(radiance.y),
                          static_cast<float>(radiance.z)};
    bright.add(glm::vec3(glm::normalize(c.centroid)), static_cast<float>(c.omega), rgb);
  }
  return bright;
}

}  // namespace penumbra::ibl
