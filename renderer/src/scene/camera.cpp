// Scene-level helpers: the default framing camera, camera lookup, triangle count.
#include <algorithm>
#include <cctype>
#include <cmath>

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

Result<int> findCamera(const Scene& scene, const std::string& nameOrIndex) {
  for (size_t i = 0; i < scene.cameras.size(); ++i) {
    if (scene.cameras[i].name == nameOrIndex) return static_cast<int>(i);
  }
  const bool numeric = !nameOrIndex.empty() && nameOrIndex.size() < 10 &&
                       std::all_of(nameOrIndex.begin(), nameOrIndex.end(), [](char c) {
                         return std::isdigit(static_cast<unsigned char>(c));
                       });
  if (numeric) {
    const size_t index = std::stoul(nameOrIndex);
    if (index < scene.cameras.size()) return static_cast<int>(index);
  }
  if (scene.cameras.empty()) {
    return makeError("no camera '" + nameOrIndex + "': the scene has no cameras");
  }
  std::string names;
  for (size_t i = 0; i < scene.cameras.size(); ++i) {
    names += (i ? ", " : "") + std::to_string(i) + ": '" + scene.cameras[i].name + "'";
  }
  return makeError("no camera '" + nameOrIndex + "'; available: " + names);
}

}  // namespace penumbra
