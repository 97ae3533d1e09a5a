// Sampling routines next to their probability densities, shared by the IBL prefilter, the DFG
// lookup table, the tests and the renderer's progressive sampler; the GLSL versions mirror these
// one for one, so change both together. Everything is in tangent space with the normal on +z,
// and GGX uses alpha = perceptualRoughness^2 throughout.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace penumbra::ibl {

inline constexpr float kPi = 3.14159265358979323846f;

inline bool isPowerOfTwo(int v) {
  return v > 0 && (v & (v - 1)) == 0;
}

// ---- Low-discrepancy points ------------------------------------------------------------------

// Van der Corput radical inverse in base 2 (bit reversal), in [0, 1).
inline float radicalInverse(uint32_t bits) {
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return static_cast<float>(bits) * 2.3283064365386963e-10f;  // / 2^32
}

// Point i of an n-point Hammersley set in [0, 1)^2. The first coordinate is centred in its
// stratum, (i + 1/2) / n, so no point sits exactly on the domain's edge.
inline glm::vec2 hammersley(uint32_t i, uint32_t n) {
  return {(static_cast<float>(i) + 0.5f) / static_cast<float>(n), radicalInverse(i)};
}

// ---- Frames ----------------------------------------------------------------------------------

// Orthonormal tangent and bitangent for a unit normal (Duff et al. 2017, branchless). The
// frame flips where n.z changes sign; the prefilter uses prefilterFrame() instead.
inline void orthonormalBasis(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

inline glm::vec3 toWorld(const glm::vec3& local, const glm::vec3& t, const glm::vec3& b,
                         const glm::vec3& n) {
  return t * local.x + b * local.y + n * local.z;
}

// Mirror reflection of v about h (both unit, v pointing away from the surface).
inline glm::vec3 reflectAbout(const glm::vec3& v, const glm::vec3& h) {
  return 2.0f * glm::dot(v, h) * h - v;
}

// ---- Cosine-weighted hemisphere (Lambert) ------------------------------------------------------

inline glm::vec3 sampleCosineHemisphere(const glm::vec2& u) {
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u.x))};
}
// Density over solid angle of sampleCosineHemisphere's direction with cos(theta) = cosTheta.
inline float pdfCosineHemisphere(float cosTheta) {
  return cosTheta > 0.0f ? cosTheta / kPi : 0.0f;
}

// ---- GGX (Trowbridge-Reitz) microfacet distribution ------------------------------------------

// D(h) for n.h = nh. Normalised so that the integral of D(h) (n.h) over the hemisphere is 1.
inline float ggxD(float nh, float alpha) {
  if (nh <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  const float d = nh * nh * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d);
}

// Samples a half vector h proportionally to D(h) (n.h) (Walter et al. 2007).
inline glm::vec3 sampleGgxD(const glm::vec2& u, float alpha) {
  const float a2 = alpha * alpha;
  const float cos2 = (1.0f - u.x) / (1.0f + (a2 - 1.0f) * u.x);
  const float cosTheta = std::sqrt(cos2);
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cos2));
  const float phi = 2.0f * kPi * u.y;
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}
// Density of sampleGgxD's half vector over solid angle.
inline float pdfGgxD(float nh, float alpha) {
  return ggxD(nh, alpha) * nh;
}
// Density over solid angle of l = reflect(v, h) when h comes from sampleGgxD:
// pdfGgxD / (4 v.h). With v = n (the split-sum prefilter) this is D(h) / 4.
inline float pdfGgxDReflected(float nh, float vh, float alpha) {
  return vh > 0.0f ? pdfGgxD(nh, alpha) / (4.0f * vh) : 0.0f;
}

// Anisotropic GGX (KHR_materials_anisotropy): D(h) with alpha_t along x (the stretch) and
// alpha_b along y. Normalised as ggxD; equal to it for alpha_t = alpha_b.
inline float ggxDAnisotropic(const glm::vec3& h, float alphaT, float alphaB) {
  if (h.z <= 0.0f) return 0.0f;
  const float x = h.x / alphaT, y = h.y / alphaB;
  const float d = x * x + y * y + h.z * h.z;
  return 1.0f / (kPi * alphaT * alphaB * d * d);
}
// Samples h proportionally to D(h) (n.h): the isotropic GGX's slope (radius
// sqrt(u.x / (1 - u.x)), angle 2 pi u.y) stretched by (alpha_t, alpha_b).
inline glm::vec3 sampleGgxDAnisotropic(const glm::vec2& u, float alphaT, float alphaB) {
  const float r = std::sqrt(u.x / std::max(1.0f - u.x, 1e-7f));
  const float phi = 2.0f * kPi * u.y;
  return glm::normalize(glm::vec3(alphaT * r * std::cos(phi), alphaB * r * std::sin(phi), 1.0f));
}
// Density of sampleGgxDAnisotropic's half vector over solid angle.
inline float pdfGgxDAnisotropic(const glm::vec3& h, float alphaT, float alphaB) {
  return ggxDAnisotropic(h, alphaT, alphaB) * std::max(h.z, 0.0f);
}

// Smith Lambda for a direction with n.w = c > 0 (G1 = 1 / (1 + Lambda)).
inline float smithLambda(float c, float alpha) {
  const float c2 = c * c;
  return 0.5f * (std::sqrt(alpha * alpha * (1.0f - c2) / c2 + 1.0f) - 1.0f);
}
inline float smithG1(float c, float alpha) {
  if (c <= 0.0f) return 0.0f;
  return 2.0f * c / (c + std::sqrt(alpha * alpha + (1.0f - alpha * alpha) * c * c));
}
// Height-correlated Smith G2(v, l) (Heitz 2014).
inline float smithG2(float nv, float nl, float alpha) {
  if (nv <= 0.0f || nl <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  const float sv = std::sqrt(a2 + (1.0f - a2) * nv * nv);
  const float sl = std::sqrt(a2 + (1.0f - a2) * nl * nl);
  return 2.0f * nv * nl / (nl * sv + nv * sl);
}
// Visibility term V = G2 / (4 n.v n.l), as in Filament's V_SmithGGXCorrelated.
inline float visibilitySmithGgx(float nv, float nl, float alpha) {
  const float a2 = alpha * alpha;
  const float sv = std::sqrt(a2 + (1.0f - a2) * nv * nv);
  const float sl = std::sqrt(a2 + (1.0f - a2) * nl * nl);
  return 0.5f / (nl * sv + nv * sl);
}

// Samples a visible normal for view direction v (v.z > 0) proportionally to
// G1(v) max(0, v.h) D(h) / v.z (Heitz 2018, "Sampling the GGX Distribution of Visible Normals").
// This form takes the polar point on the unit disc (r = sqrt(u.x), phi = 2 pi u.y) so callers
// that reuse one point set for many v can precompute the trigonometry.
inline glm::vec3 sampleGgxVndfPolar(const glm::vec3& v, float r, float cosPhi, float sinPhi,
                                    float alpha) {
  const glm::vec3 vh = glm::normalize(glm::vec3(alpha * v.x, alpha * v.y, v.z));
  const float lensq = vh.x * vh.x + vh.y * vh.y;
  const glm::vec3 t1 =
      lensq > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq) : glm::vec3(1, 0, 0);
  const glm::vec3 t2 = glm::cross(vh, t1);
  const float p1 = r * cosPhi;
  const float s = 0.5f * (1.0f + vh.z);
  const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * sinPhi;
  const glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(0.0f, nh.z)));
}
inline glm::vec3 sampleGgxVndf(const glm::vec3& v, const glm::vec2& u, float alpha) {
  const float phi = 2.0f * kPi * u.y;
  return sampleGgxVndfPolar(v, std::sqrt(u.x), std::cos(phi), std::sin(phi), alpha);
}
// Density of sampleGgxVndf's half vector over solid angle.
inline float pdfGgxVndf(const glm::vec3& v, const glm::vec3& h, float alpha) {
  const float vh = glm::dot(v, h);
  if (v.z <= 0.0f || vh <= 0.0f) return 0.0f;
  return smithG1(v.z, alpha) * vh * ggxD(h.z, alpha) / v.z;
}
// Density over solid angle of l = reflect(v, h) with h from sampleGgxVndf: pdfGgxVndf / (4 v.h).
inline float pdfGgxVndfReflected(const glm::vec3& v, const glm::vec3& h, float alpha) {
  const float vh = glm::dot(v, h);
  return vh > 0.0f ? pdfGgxVndf(v, h, alpha) / (4.0f * vh) : 0.0f;
}

}  // namespace penumbra::ibl
