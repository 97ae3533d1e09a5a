// Generated vertex normals and tangents.
//
// Tangents follow MikkTSpace (the glTF reference tangent space) in everything that decides a
// vertex's tangent on ordinary meshes:
//  - per-triangle tangent direction from the UV derivatives, (e1 * dv2 - e2 * dv1) * sign(r)
//    with r the signed UV area, as MikkTSpace's vOs;
//  - handedness (tangent.w) = the sign of the triangle's UV area, as MikkTSpace's bOrient,
//    computed on (u, 1 - v) as exporters do, so bitangent = w * cross(normal, tangent) points
//    "up" the image (toward decreasing glTF v), glTF's normal-map convention;
//  - per corner, the triangle tangent is projected onto the plane of the vertex normal,
//    normalised and weighted by the corner angle, then accumulated per vertex;
//  - a vertex shared by triangles of opposite handedness (a mirrored UV seam that shares
//    vertices) is split, so each side keeps its own sign instead of averaging to nothing;
//  - triangles with zero UV area or zero geometric area contribute nothing;
//  - the result is Gram-Schmidt orthogonalised against the vertex normal.
// Differences: MikkTSpace welds vertices itself by comparing position, normal and UV, whereas we
// take sharing from the index buffer (glTF exporters already weld identical vertices); it groups
// and splits further by connectivity within one handedness, which only matters for unusual
// meshes; and it fills vertices that only touch degenerate triangles from their neighbours,
// where we use an arbitrary unit vector perpendicular to the normal. No MikkTSpace reference
// implementation is packaged for Debian, so the match has not been checked numerically.
#include <cmath>
#include <limits>

#include "scene/gltf_document.h"

namespace penumbra::gltf {
namespace {

glm::vec3 anyPerpendicular(const glm::vec3& n) {
  const glm::vec3 axis = std::fabs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(axis - n * glm::dot(n, axis));
}

// Appends a copy of vertex `v` (every attribute present) and returns its index.
uint32_t cloneVertex(Primitive& p, uint32_t v) {
  p.positions.push_back(p.positions[v]);
  if (!p.normals.empty()) p.normals.push_back(p.normals[v]);
  if (!p.tangents.empty()) p.tangents.push_back(p.tangents[v]);
  if (!p.uv0.empty()) p.uv0.push_back(p.uv0[v]);
  if (!p.uv1.empty()) p.uv1.push_back(p.uv1[v]);
  if (!p.colors.empty()) p.colors.push_back(p.colors[v]);
  return static_cast<uint32_t>(p.positions.size() - 1);
}

float cornerAngle(const glm::vec3& at, const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 u = a - at;
  const glm::vec3 w = b - at;
  const float lu = glm::length(u);
  const float lw = glm::length(w);
  if (lu <= 0.0f || lw <= 0.0f) return 0.0f;
  return std::acos(glm::clamp(glm::dot(u, w) / (lu * lw), -1.0f, 1.0f));
}

}  // namespace

void generateNormals(Primitive& p) {
  p.normals.assign(p.positions.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
    const uint32_t i0 = p.indices[t], i1 = p.indices[t + 1], i2 = p.indices[t + 2];
    // The cross product's length is twice the triangle's area: area weighting for free.
    const glm::vec3 n =
        glm::cross(p.positions[i1] - p.positions[i0], p.positions[i2] - p.positions[i0]);
    p.normals[i0] += n;
    p.normals[i1] += n;
    p.normals[i2] += n;
  }
  for (glm::vec3& n : p.normals) {
    const float len = glm::length(n);
    n = len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0, 0, 1);
  }
}

void unweldVertices(Primitive& p) {
  Primitive out;
  out.material = p.material;
  out.variantMaterials = p.variantMaterials;
  out.bounds = p.bounds;
  const size_t n = p.indices.size();
  out.positions.reserve(n);
  for (uint32_t i : p.indices) {
    out.positions.push_back(p.positions[i]);
    if (!p.normals.empty()) out.normals.push_back(p.normals[i]);
    if (!p.tangents.empty()) out.tangents.push_back(p.tangents[i]);
    if (!p.uv0.empty()) out.uv0.push_back(p.uv0[i]);
    if (!p.uv1.empty()) out.uv1.push_back(p.uv1[i]);
    if (!p.colors.empty()) out.colors.push_back(p.colors[i]);
  }
  out.indices.resize(n);
  for (size_t i = 0; i < n; ++i) out.indices[i] = static_cast<uint32_t>(i);
  p = std::move(out);
}

void generateTangents(Primitive& p, int uvSet) {
  if (p.normals.size() != p.positions.size()) generateNormals(p);
  const std::vector<glm::vec2>* uv = uvSet == 0 ? &p.uv0 : (uvSet == 1 ? &p.uv1 : nullptr);
  if (uv && uv->size() != p.positions.size()) uv = nullptr;
  if (!uv) {
    p.tangents.resize(p.positions.size());
    for (size_t v = 0; v < p.positions.size(); ++v) {
      p.tangents[v] = glm::vec4(anyPerpendicular(p.normals[v]), 1.0f);
    }
    return;
  }

  const size_t faces = p.indices.size() / 3;
  std::vector<glm::vec3> faceTangent(faces);
  std::vector<int8_t> faceSign(faces, 0);  // 0 = degenerate, contributes nothing
  for (size_t f = 0; f < faces; ++f) {
    const uint32_t i0 = p.indices[3 * f], i1 = p.indices[3 * f + 1], i2 = p.indices[3 * f + 2];
    const glm::vec3 e1 = p.positions[i1] - p.positions[i0];
    const glm::vec3 e2 = p.positions[i2] - p.positions[i0];
    const glm::vec2 d1 = (*uv)[i1] - (*uv)[i0];
    const glm::vec2 d2 = (*uv)[i2] - (*uv)[i0];
    const float r = d1.x * d2.y - d2.x * d1.y;
    const float area = glm::length(glm::cross(e1, e2));
    if (!(std::fabs(r) > std::numeric_limits<float>::min()) || !(area > 0.0f)) continue;
    const float orient = r > 0.0f ? 1.0f : -1.0f;
    faceTangent[f] = (e1 * d2.y - e2 * d1.y) * orient;
    // glTF's v axis points down the image while MikkTSpace (as Blender runs it before the
    // exporter flips v) works with v up: the tangent is unchanged by that flip, the
    // handedness is negated. So an upright texture on a quad gets w = +1.
    faceSign[f] = static_cast<int8_t>(-orient);
  }

  // Split vertices shared by triangles of opposite handedness: the clone serves the
  // negative-handedness triangles.
  const size_t originalCount = p.positions.size();
  std::vector<uint8_t> signs(originalCount, 0);  // bit 0: positive seen, bit 1: negative seen
  for (size_t f = 0; f < faces; ++f) {
    if (faceSign[f] == 0) continue;
    for (int k = 0; k < 3; ++k)
      signs[p.indices[3 * f + static_cast<size_t>(k)]] |= faceSign[f] > 0 ? 1 : 2;
  }
  std::vector<uint32_t> cloneOf(originalCount, UINT32_MAX);
  for (size_t f = 0; f < faces; ++f) {
    if (faceSign[f] >= 0) continue;
    for (int k = 0; k < 3; ++k) {
      uint32_t& idx = p.indices[3 * f + static_cast<size_t>(k)];
      if (idx >= originalCount || signs[idx] != 3) continue;
      if (cloneOf[idx] == UINT32_MAX) cloneOf[idx] = cloneVertex(p, idx);
      idx = cloneOf[idx];
    }
  }
  uv = uvSet == 0 ? &p.uv0 : &p.uv1;  // cloning may have reallocated the arrays

  const size_t n = p.positions.size();
  std::vector<glm::vec3> acc(n, glm::vec3(0.0f));
  std::vector<int8_t> vertexSign(n, 0);
  for (size_t f = 0; f < faces; ++f) {
    if (faceSign[f] == 0) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = p.indices[3 * f + static_cast<size_t>(k)];
      const uint32_t a = p.indices[3 * f + static_cast<size_t>((k + 1) % 3)];
      const uint32_t b = p.indices[3 * f + static_cast<size_t>((k + 2) % 3)];
      const glm::vec3& nv = p.normals[v];
      glm::vec3 t = faceTangent[f] - nv * glm::dot(nv, faceTangent[f]);
      const float len = glm::length(t);
      if (!(len > 0.0f) || !std::isfinite(len)) continue;
      t /= len;
      acc[v] += t * cornerAngle(p.positions[v], p.positions[a], p.positions[b]);
      vertexSign[v] = faceSign[f];
    }
  }

  p.tangents.resize(n);
  for (size_t v = 0; v < n; ++v) {
    const glm::vec3& nv = p.normals[v];
    glm::vec3 t = acc[v] - nv * glm::dot(nv, acc[v]);
    const float len = glm::length(t);
    t = len > 1e-12f && std::isfinite(len) ? t / len : anyPerpendicular(nv);
    p.tangents[v] = glm::vec4(t, vertexSign[v] < 0 ? -1.0f : 1.0f);
  }
}

}  // namespace penumbra::gltf
