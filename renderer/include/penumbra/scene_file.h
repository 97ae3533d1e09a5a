// SceneFile: Penumbra's JSON scene description (docs/scene-format.md) — which glTF to render,
// the environment, the camera, and the render and progressive settings. A .gltf/.glb can also
// stand for itself with default settings. Command-line flags override what the file says.
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "penumbra/error.h"
#include "penumbra/settings.h"

namespace penumbra {

struct SceneFile {
  std::string gltfPath;         // resolved against the scene file's folder
  std::string environmentPath;  // empty: a uniform environment of `uniformEnvironment`
  glm::vec3 uniformEnvironment{1.0f};
  std::string camera;  // name or index; empty: the first camera, else a default one
  RenderSettings settings;
  std::vector<std::string> warnings;  // unknown keys and the like
};

// Reads a scene file (.json) or wraps a .gltf/.glb with defaults.
Result<SceneFile> loadSceneFile(const std::string& path);
// Parses scene JSON text; relative paths are resolved against `baseDir`.
Result<SceneFile> parseSceneJson(const std::string& text, const std::string& baseDir,
                                 const std::string& nameForErrors);

}  // namespace penumbra
