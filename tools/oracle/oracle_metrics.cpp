#include "oracle_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace oracle {

Difference difference(const Frame8& a, const Frame8& b) {
  constexpr int kTile = 8;
  const int tw = (a.width + kTile - 1) / kTile, th = (a.height + kTile - 1) / kTile;
  std::vector<double> tileSum(static_cast<size_t>(tw) * th, 0.0), tileCount(tileSum.size(), 0.0);
  double sum = 0.0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const size_t p = (static_cast<size_t>(y) * a.width + x) * 3;
      const size_t t = static_cast<size_t>(y / kTile) * tw + x / kTile;
      for (int c = 0; c < 3; ++c) {
        const double d = static_cast<double>(a.rgb[p + c]) - b.rgb[p + c];
        sum += d * d;
        tileSum[t] += d * d;
        tileCount[t] += 1.0;
      }
    }
  }
  Difference out;
  out.rms = std::sqrt(sum / std::max<double>(1.0, static_cast<double>(a.rgb.size())));
  std::vector<double> tiles(tileSum.size());
  for (size_t i = 0; i < tiles.size(); ++i) tiles[i] = std::sqrt(tileSum[i] / tileCount[i]);
  const size_t k =
      std::min(tiles.size() - 1,
               static_cast<size_t>(std::ceil(0.99 * static_cast<double>(tiles.size()))) - 1);
  std::nth_element(tiles.begin(), tiles.begin() + static_cast<std::ptrdiff_t>(k), tiles.end());
  out.tileP99 = tiles[k];
  return out;
}

int oracleFrame(const std::vector<Difference>& perFrame) {
  int frame = 0;
  for (int i = static_cast<int>(perFrame.size()); i >= 1; --i) {
    if (!acceptable(perFrame[static_cast<size_t>(i - 1)])) break;
    frame = i;
  }
  return frame;
}

namespace {

// image minus its 3x3 median, one channel, at an interior pixel
double highPass(const Frame8& f, int x, int y, int c) {
  std::array<uint8_t, 9> v{};
  int n = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      v[static_cast<size_t>(n++)] =
          f.rgb[(static_cast<size_t>(y + dy) * f.width + (x + dx)) * 3 + static_cast<size_t>(c)];
    }
  }
  std::nth_element(v.begin(), v.begin() + 4, v.end());
  return static_cast<double>(
             f.rgb[(static_cast<size_t>(y) * f.width + x) * 3 + static_cast<size_t>(c)]) -
         v[4];
}

}  // namespace

double excessGrain(const Frame8& image, const Frame8& converged) {
  double sum = 0.0;
  size_t count = 0;
  for (int y = 1; y + 1 < image.height; ++y) {
    for (int x = 1; x + 1 < image.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const double d = highPass(image, x, y, c) - highPass(converged, x, y, c);
        sum += d * d;
        ++count;
      }
    }
  }
  return count ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
}

}  // namespace oracle
