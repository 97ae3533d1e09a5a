// The stopping oracle's measures on displayed 8-bit images (RGB, 3 bytes a pixel, row-major):
// the RMS difference and the 99th-percentile tile RMS in 8-bit steps, the oracle frame of a
// sequence, and the excess high-frequency noise ("grain") of an image over a converged one.
#pragma once

#include <cstdint>
#include <vector>

namespace oracle {

struct Frame8 {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
};

struct Difference {
  double rms = 0;      // over every channel of every pixel, 8-bit steps
  double tileP99 = 0;  // 99th percentile of the 8x8 tiles' RMS, 8-bit steps
};

Difference difference(const Frame8& a, const Frame8& b);

// The oracle: within 1/255 RMS of the reference with 99 % of the tiles within 3/255.
inline bool acceptable(const Difference& d) {
  return d.rms <= 1.0 && d.tileP99 <= 3.0;
}

// The first frame (1-based) from which every later frame is acceptable; 0 if the last is not.
int oracleFrame(const std::vector<Difference>& perFrame);

// The RMS (8-bit steps) of the image's high frequencies (image minus its 3x3 median, per
// channel) less the converged image's: the grain a person sees that the final picture lacks.
double excessGrain(const Frame8& image, const Frame8& converged);

}  // namespace oracle
