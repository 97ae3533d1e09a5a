// Scene-level helpers: the default framing camera, camera and variant lookup, triangle count.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene.h"

namespace penumbra {

size_t Scene::triangleCount() const {
  size_t count = 0;
  for (const Instance& inst : instances) {
    if (inst.mesh < 0 || static_cast<size_t>(inst.mesh) >= meshes.size()) continue;
    for (const Primitive& p : meshes[static_cast<size_t>(inst.mesh)].primitives) {
      count += p.indices.size() / 3;
    }
  }
  return count;
}

namespace {

// What the automatic framing fits: every vertex of every instance while that stays cheap (about
// a million), else the corners of each instance's primitive bounds, else the scene's bounds.
std::vector<glm::vec3> framingPoints(const Scene& scene) {
  constexpr size_t kVertexBudget = size_t{1} << 20;
  size_t vertices = 0;
  for (const Instance& inst : scene.instances) {
    if (inst.mesh < 0 || static_cast<size_t>(inst.mesh) >= scene.meshes.size()) continue;
    for (const Primitive& p : scene.meshes[static_cast<size_t>(inst.mesh)].primitives) {
      vertices += p.positions.size();
    }
  }
  std::vector<glm::vec3> points;
  auto corners = [&](const Bounds& b, const glm::mat4& world) {
    if (!b.valid()) return;
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 p((c & 1) ? b.max.x : b.min.x, (c & 2) ? b.max.y : b.min.y,
                        (c & 4) ? b.max.z : b.min.z);
      points.emplace_back(world * glm::vec4(p, 1.0f));
    }
  };
  for (const Instance& inst : scene.instances) {
    if (inst.mesh < 0 || static_cast<size_t>(inst.mesh) >= scene.meshes.size()) continue;
    for (const Primitive& p : scene.meshes[static_cast<size_t>(inst.mesh)].primitives) {
      if (vertices > kVertexBudget) {
        corners(p.bounds, inst.world);
        continue;
      }
      // Each vertex once (the index list names most of them several times).
      for (const glm::vec3& v : p.positions) points.emplace_back(inst.world * glm::vec4(v, 1.0f));
    }
  }
  std::erase_if(points, [](const glm::vec3& p) {
    return !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z);
  });
  if (points.empty()) corners(scene.bounds, glm::mat4(1.0f));
  return points;
}

// The aim's offset along one view axis that centres the points seen from `distance`: where
// the largest and the smallest projected coordinate (c - s) / (distance - z) cancel. Their sum
// falls as s grows, so bisection finds it. (The distance's fit centres the binding axis in its
// own terms; a deep model's other axis needs the projection's.)
float centringOffset(const std::vector<glm::vec2>& cz, float distance) {
  float lo = 1e30f, hi = -1e30f;
  for (const glm::vec2& p : cz) {
    lo = std::min(lo, p.x);
    hi = std::max(hi, p.x);
  }
  for (int i = 0; i < 32 && lo < hi; ++i) {
    const float s = 0.5f * (lo + hi);
    float most = -1e30f, least = 1e30f;
    for (const glm::vec2& p : cz) {
      const float q = (p.x - s) / (distance - p.y);
      most = std::max(most, q);
      least = std::min(least, q);
    }
    (most + least > 0.0f ? lo : hi) = s;
  }
  return 0.5f * (lo + hi);
}

}  // namespace

Camera defaultCamera(const Scene& scene, float aspect) {
  constexpr float kFov = 0.785398163f;  // 45 degrees vertical
  // The model fills this share of the view's binding extent, as model-viewer leaves a margin.
  constexpr float kFill = 0.92f;
  if (!(aspect > 0.0f) || !std::isfinite(aspect)) aspect = 1.0f;
  // From +Z, raised about 14 degrees so the ground plane of a typical scene is visible.
  const glm::vec3 back = glm::normalize(glm::vec3(0.0f, 0.25f, 1.0f));  // centre -> eye
  const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0, 1, 0), back));
  const glm::vec3 up = glm::cross(back, right);
  const float tanY = std::tan(kFov * 0.5f) * kFill, tanX = tanY * aspect;

  const std::vector<glm::vec3> points = framingPoints(scene);
  glm::vec3 origin(0.0f);
  if (scene.bounds.valid()) origin = scene.bounds.center();
  // A point at lateral offsets (x, y) and depth offset z toward the eye is in view from
  // distance D when D >= |x| / tanX + z (and the same for y). Shifting the aim by s along an
  // axis turns the bound into max(A - s/t, B + s/t), least at s = t (A - B) / 2 with value
  // (A + B) / 2: as tight as the binding axis allows, the aim then centred at that distance.
  float ax = -1e30f, bx = -1e30f, ay = -1e30f, by = -1e30f, zMax = -1e30f;
  for (const glm::vec3& p : points) {
    const glm::vec3 d = p - origin;
    const float x = glm::dot(d, right), y = glm::dot(d, up), z = glm::dot(d, back);
    ax = std::max(ax, x / tanX + z);
    bx = std::max(bx, -x / tanX + z);
    ay = std::max(ay, y / tanY + z);
    by = std::max(by, -y / tanY + z);
    zMax = std::max(zMax, z);
  }
  float distance = 1.0f / std::sin(kFov * 0.5f);  // an empty scene: a unit sphere's framing
  glm::vec3 center = origin;
  if (!points.empty()) {
    distance = std::max(0.5f * (ax + bx), 0.5f * (ay + by));
    // A point model (or a degenerate one): back off so something of it is in front.
    const float extent = std::max(ax + bx, ay + by);
    distance = std::max(distance, zMax + std::max(extent, 1e-6f) * 0.05f);
    if (!(distance > 0.0f) || !std::isfinite(distance)) distance = 1.0f;
    std::vector<glm::vec2> xz(points.size()), yz(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      const glm::vec3 d = points[i] - origin;
      xz[i] = {glm::dot(d, right), glm::dot(d, back)};
      yz[i] = {glm::dot(d, up), xz[i].y};
    }
    center += right * centringOffset(xz, distance) + up * centringOffset(yz, distance);
  }
  const glm::vec3 eye = center + back * distance;

  Camera cam;
  cam.name = "default";
  cam.world = glm::inverse(glm::lookAt(eye, center, glm::vec3(0, 1, 0)));
  cam.yfov = kFov;
  // Fitted to this aspect: a narrower (portrait) viewport keeps the horizontal extent.
  cam.aspect = aspect;
  const float nearest = points.empty() ? distance * 0.5f : distance - zMax;
  cam.znear = std::max(nearest, distance * 0.01f) * 0.5f;
  cam.zfar = 0.0f;
  return cam;
}

namespace {

// The index of `nameOrIndex` among `names` (a name first, then a number); `what` names the kind
// in the one-line error, which lists what there is.
Result<int> findNamed(const std::vector<std::string>& names, const std::string& nameOrIndex,
                      const std::string& what, const std::string& plural) {
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == nameOrIndex) return static_cast<int>(i);
  }
  const bool numeric = !nameOrIndex.empty() && nameOrIndex.size() < 10 &&
                       std::all_of(nameOrIndex.begin(), nameOrIndex.end(), [](char c) {
                         return std::isdigit(static_cast<unsigned char>(c));
                       });
  if (numeric) {
    const size_t index = std::stoul(nameOrIndex);
    if (index < names.size()) return static_cast<int>(index);
  }
  if (names.empty()) {
    return makeError("no " + what + " '" + nameOrIndex + "': the scene has no " + plural);
  }
  std::string list;
  for (size_t i = 0; i < names.size(); ++i) {
    list += (i ? ", " : "") + std::to_string(i) + ": '" + names[i] + "'";
  }
  return makeError("no " + what + " '" + nameOrIndex + "'; available: " + list);
}

}  // namespace

Result<int> findCamera(const Scene& scene, const std::string& nameOrIndex) {
  std::vector<std::string> names;
  for (const Camera& c : scene.cameras) names.push_back(c.name);
  return findNamed(names, nameOrIndex, "camera", "cameras");
}

Result<int> findVariant(const Scene& scene, const std::string& nameOrIndex) {
  if (nameOrIndex.empty() || nameOrIndex == "default") return -1;
  return findNamed(scene.variants, nameOrIndex, "variant", "material variants");
}

}  // namespace penumbra
