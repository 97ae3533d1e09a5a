// Sun extraction: the brightest compact region of a panorama becomes a distant disk light, so
// it can cast shadows, and its excess radiance leaves the panorama, so no energy is counted
// twice (what Eevee's world "sun threshold" does). See docs/ibl.md, "The sun".
#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "penumbra/ibl.h"

namespace penumbra::ibl {
namespace {

constexpr double kPiD = 3.14159265358979323846;

float luminance(const float* p, int channels) {
  if (channels < 3) return p[0];
  return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
}

}  // namespace

std::optional<Sun> extractSun(Image& panorama, const SunOptions& options) {
  const int w = panorama.width, h = panorama.height, ch = panorama.channels;
  if (options.threshold == 0.0f || w < 2 || h < 1 || w != 2 * h || ch < 1) return std::nullopt;
  const auto pixel = [&](int x, int y) {
    return &panorama.pixels[(static_cast<size_t>(y) * w + x) * ch];
  };
  // Solid angle of a pixel of row y: (2 pi / w) (pi / h) sin(polar angle).
  std::vector<double> rowOmega(static_cast<size_t>(h));
  for (int y = 0; y < h; ++y) {
    rowOmega[static_cast<size_t>(y)] = (2.0 * kPiD / w) * (kPiD / h) * std::sin(kPiD * (y + 0.5) / h);
  }
  double total = 0.0;
  float peak = 0.0f;
  int peakX = 0, peakY = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const float l = luminance(pixel(x, y), ch);
      total += l * rowOmega[static_cast<size_t>(y)];
      if (l > peak) {
        peak = l;
        peakX = x;
        peakY = y;
      }
    }
  }
  const bool automatic = options.threshold < 0.0f;
  const double mean = total / (4.0 * kPiD);
  const float threshold =
      automatic ? static_cast<float>(kSunAutoMeanMultiple * mean) : options.threshold;
  if (!(peak > threshold) || !(threshold > 0.0f)) return std::nullopt;

  // The connected region above the threshold around the peak (4-neighbours, wrapping in x).
  // An automatic sun is compact: stop as soon as the region is larger than a sun may be.
  const double maxOmega = 2.0 * kPiD * (1.0 - std::cos(static_cast<double>(kSunMaxAngularRadius)));
  std::vector<uint8_t> seen(static_cast<size_t>(w) * h, 0);
  std::vector<int> region, stack{peakY * w + peakX};
  seen[static_cast<size_t>(stack.back())] = 1;
  double regionOmega = 0.0;
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    region.push_back(i);
    const int x = i % w, y = i / w;
    regionOmega += rowOmega[static_cast<size_t>(y)];
    if (automatic && regionOmega > maxOmega) return std::nullopt;
    const int next[4][2] = {{(x + 1) % w, y}, {(x + w - 1) % w, y}, {x, y - 1}, {x, y + 1}};
    for (const auto& n : next) {
      if (n[1] < 0 || n[1] >= h) continue;
      const int j = n[1] * w + n[0];
      if (seen[static_cast<size_t>(j)] || !(luminance(pixel(n[0], n[1]), ch) > threshold)) continue;
      seen[static_cast<size_t>(j)] = 1;
      stack.push_back(j);
    }
  }

  // The excess above the threshold, hue kept: its energy and energy-weighted direction.
  glm::dvec3 energy(0.0), centroid(0.0);
  double excessLuminance = 0.0;
  for (const int i : region) {
    const int x = i % w, y = i / w;
    const float* p = pixel(x, y);
    const float l = luminance(p, ch);
    const double omega = rowOmega[static_cast<size_t>(y)];
    const double keep = threshold / l;
    for (int c = 0; c < 3; ++c) energy[c] += p[std::min(c, ch - 1)] * (1.0 - keep) * omega;
    const glm::vec3 d = panoramaDirection((x + 0.5f) / w, (y + 0.5f) / h);
    centroid += glm::dvec3(d) * ((l - threshold) * omega);
    excessLuminance += (l - threshold) * omega;
  }
  if (!(excessLuminance > 0.0)) return std::nullopt;
  if (automatic && excessLuminance < kSunMinShare * total) return std::nullopt;
  const glm::dvec3 direction = glm::normalize(centroid);
  // A uniform disk of angular radius r has a mean squared angle of r^2 / 2 about its centre.
  double meanAngle2 = 0.0;
  for (const int i : region) {
    const int x = i % w, y = i / w;
    const float l = luminance(pixel(x, y), ch);
    const glm::dvec3 d(panoramaDirection((x + 0.5f) / w, (y + 0.5f) / h));
    const double angle = std::acos(std::clamp(glm::dot(d, direction), -1.0, 1.0));
    meanAngle2 += angle * angle * (l - threshold) * rowOmega[static_cast<size_t>(y)];
  }
  meanAngle2 /= excessLuminance;
  const double radius = std::sqrt(2.0 * meanAngle2);
  if (automatic && radius > kSunMaxAngularRadius) return std::nullopt;

  for (const int i : region) {
    float* p = &panorama.pixels[static_cast<size_t>(i) * ch];
    const float keep = threshold / luminance(p, ch);
    for (int c = 0; c < std::min(ch, 3); ++c) p[c] *= keep;
  }
  Sun sun;
  sun.direction = glm::vec3(direction);
  // At least a quarter of a pixel: a sun narrower than the panorama resolves has that size.
  sun.angularRadius = static_cast<float>(std::max(radius, 0.25 * kPiD / h));
  sun.irradiance = glm::vec3(energy);
  sun.threshold = threshold;
  return sun;
}

}  // namespace penumbra::ibl
