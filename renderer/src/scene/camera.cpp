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

Camera defaultCamera(const Scene& scene) {
  constexpr float kFov = 0.785398163f;  // 45 degrees vertical
  glm::vec3 center(0.0f);
  float radius = 1.0f;
  if (scene.bounds.valid()) {
    center = scene.bounds.center();
    radius = scene.bounds.radius();
    if (!(radius > 0.0f) || !std::isfinite(radius)) radius = 1.0f;
  }
  // The bounding sphere touches the top and bottom of a square view at this distance.
  const float distance = radius / std::sin(kFov * 0.5f);
  // From +Z, raised about 14 degrees so the ground plane of a typical scene is visible.
  const glm::vec3 dir = glm::normalize(glm::vec3(0.0f, 0.25f, 1.0f));
  const glm::vec3 eye = center + dir * distance;

  Camera cam;
  cam.name = "default";
  cam.world = glm::inverse(glm::lookAt(eye, center, glm::vec3(0, 1, 0)));
  cam.yfov = kFov;
  // The bounding sphere fits a square: in a portrait view the horizontal extent is kept.
  cam.aspect = 1.0f;
  cam.znear = std::max(distance - radius, distance * 0.01f) * 0.5f;
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
