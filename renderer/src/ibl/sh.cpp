// Order-2 spherical harmonics of environment radiance, and irradiance from them
// (Ramamoorthi & Hanrahan 2001, "An Efficient Representation for Irradiance Environment Maps").
#include <cmath>
#include <cstdio>
#include <string>

#include "ibl/parallel.h"
#include "ibl/sampling.h"
#include "image/image_internal.h"
#include "penumbra/ibl.h"

namespace penumbra::ibl {

std::array<float, 9> shBasis(const glm::vec3& n) {
  return {
      0.282094792f,                              // Y00
      0.488602512f * n.y,                        // Y1-1
      0.488602512f * n.z,                        // Y10
      0.488602512f * n.x,                        // Y11
      1.092548431f * n.x * n.y,                  // Y2-2
      1.092548431f * n.y * n.z,                  // Y2-1
      0.315391565f * (3.0f * n.z * n.z - 1.0f),  // Y20
      1.092548431f * n.x * n.z,                  // Y21
      0.546274215f * (n.x * n.x - n.y * n.y),    // Y22
  };
}

ShCoefficients projectSh(const Cubemap& cube, int mip, int threads) {
  PN_CHECK(mip >= 0 && mip < cube.mipCount(), "mip out of range");
  const int n = cube.faceSize(mip);
  for (const Image& face : cube.mips[mip]) {
    PN_CHECK(face.width == n && face.height == n && face.channels == 3, "faces must be n x n RGB");
  }
  // One partial sum per face row, added up in a fixed order afterwards: the result does not
  // depend on the thread count. Doubles keep the 4 pi of a constant environment exact enough.
  std::vector<std::array<double, 27>> rows(static_cast<size_t>(kFaceCount) * n);
  const std::vector<double> omega = texelSolidAngles(n);
  parallelFor(kFaceCount * n, threads, [&](int row) {
    const int face = row / n;
    const int y = row % n;
    std::array<double, 27>& sum = rows[row];
    sum.fill(0.0);
    const Image& image = cube.face(mip, face);
    for (int x = 0; x < n; ++x) {
      const double w = omega[static_cast<size_t>(y) * n + x];
      const std::array<float, 9> basis = shBasis(texelDirection(face, x, y, n));
      const float* p = image.pixel(x, y);
      for (int i = 0; i < 9; ++i) {
        for (int k = 0; k < 3; ++k) sum[i * 3 + k] += w * basis[i] * p[k];
      }
    }
  });
  std::array<double, 27> total{};
  for (const auto& r : rows) {
    for (int i = 0; i < 27; ++i) total[i] += r[i];
  }
  ShCoefficients sh;
  for (int i = 0; i < 9; ++i) {
    sh.c[i] = glm::vec3(static_cast<float>(total[i * 3]), static_cast<float>(total[i * 3 + 1]),
                        static_cast<float>(total[i * 3 + 2]));
  }
  return sh;
}

glm::vec3 evaluateShRadiance(const ShCoefficients& sh, const glm::vec3& n) {
  const std::array<float, 9> basis = shBasis(n);
  glm::vec3 out(0.0f);
  for (int i = 0; i < 9; ++i) out += sh.c[i] * basis[i];
  return out;
}

glm::vec3 evaluateIrradiance(const ShCoefficients& sh, const glm::vec3& n) {
  // Cosine-lobe convolution per band: A0 = pi, A1 = 2 pi / 3, A2 = pi / 4.
  static constexpr float kBand[9] = {
      kPi,        2.0f * kPi / 3.0f, 2.0f * kPi / 3.0f, 2.0f * kPi / 3.0f, kPi / 4.0f,
      kPi / 4.0f, kPi / 4.0f,        kPi / 4.0f,        kPi / 4.0f};
  const std::array<float, 9> basis = shBasis(n);
  glm::vec3 out(0.0f);
  for (int i = 0; i < 9; ++i) out += sh.c[i] * (kBand[i] * basis[i]);
  return out;
}

std::string shToJson(const ShCoefficients& sh) {
  std::string out =
      "{\"convention\":\"radiance SH, E(n) = sum_l A_l sum_m L_lm Y_lm(n), A = (pi, 2pi/3, "
      "pi/4); Lambert: albedo * E / pi\",\"basis\":[\"0.282095\",\"0.488603 y\",\"0.488603 z\","
      "\"0.488603 x\",\"1.092548 x y\",\"1.092548 y z\",\"0.315392 (3 z^2 - 1)\","
      "\"1.092548 x z\",\"0.546274 (x^2 - y^2)\"],\"frame\":\"glTF world, +Y up\","
      "\"coefficients\":[";
  char buffer[128];
  for (int i = 0; i < 9; ++i) {
    std::snprintf(buffer, sizeof buffer, "%s[%.9g,%.9g,%.9g]", i ? "," : "", sh.c[i].x, sh.c[i].y,
                  sh.c[i].z);
    out += buffer;
  }
  out += "]}";
  return out;
}

Status writeShJson(const std::string& path, const ShCoefficients& sh) {
  const std::string text = shToJson(sh) + "\n";
  return detail::writeFileAtomic(
      path, std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

}  // namespace penumbra::ibl
