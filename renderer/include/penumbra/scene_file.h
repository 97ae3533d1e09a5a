// SceneFile: Penumbra's JSON scene description (docs/scene-format.md) — which glTF to render,
// the environment, the camera, and the render and progressive settings. A .gltf/.glb can also
// stand for itself with default settings. Command-line flags override what the file says.
// The settings part is read and written through the settings schema (penumbra/settings.h).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "penumbra/error.h"
#include "penumbra/settings.h"

namespace penumbra {

// Where the world's light comes from.
struct EnvironmentSpec {
  enum class Kind {
    Default,  // by rule: black when the scene has lights of its own, else the studio
    None,     // black
    Studio,   // the neutral studio environment shipped with Penumbra (studioEnvironment())
    File,     // a packed environment or an HDR panorama
    Uniform,  // constant radiance
  };
  Kind kind = Kind::Default;
  std::string path;          // File
  glm::vec3 radiance{0.0f};  // Uniform
};

// "none", "studio", "r,g,b" (uniform radiance) or a file name (resolved against `baseDir`).
Result<EnvironmentSpec> parseEnvironmentSpec(std::string_view text,
                                             const std::string& baseDir = "");
// The form parseEnvironmentSpec reads ("default" for Kind::Default).
std::string environmentSpecText(const EnvironmentSpec& spec);

// The probe volume's box and probe counts, when the scene file overrides them ("probeVolume":
// {"min": [x, y, z], "max": [x, y, z], "counts": [nx, ny, nz]}, each part optional).
struct ProbeVolumeSpec {
  bool hasBox = false;
  glm::vec3 min{0.0f}, max{0.0f};
  glm::ivec3 counts{0};  // 0 on an axis: from the density setting
};

struct SceneFile {
  std::string gltfPath;  // resolved against the scene file's folder
  EnvironmentSpec environment;
  std::string camera;   // name or index; empty: the first camera, else a default one
  std::string variant;  // KHR_materials_variants name or index; empty: the default materials
  // A glTF animation (name or index) and the time in seconds to pose the model at; empty: at
  // rest (a time alone poses the first animation, as model-viewer plays the first).
  std::string animation;
  std::optional<float> time;
  ProbeVolumeSpec probeVolume;
  RenderSettings settings;
  std::vector<std::string> warnings;  // unknown keys and the like
};

// Reads a scene file (.json) or wraps a .gltf/.glb with defaults.
Result<SceneFile> loadSceneFile(const std::string& path);
// Parses scene JSON text; relative paths are resolved against `baseDir`.
Result<SceneFile> parseSceneJson(const std::string& text, const std::string& baseDir,
                                 const std::string& nameForErrors);
// Writes a scene file that parseSceneJson reads back to the same SceneFile (paths as given:
// relative ones stay relative to wherever the text is saved). Every setting is written.
std::string sceneFileJson(const SceneFile& sceneFile);

}  // namespace penumbra
