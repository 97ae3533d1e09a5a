// Internals the web viewer's wasm exports share (viewer_main.cpp, viewer_environment.cpp): the
// one Viewer a module instance serves, and how an export answers JS (JSON text; a C++
// exception or an error never crosses into JS as a throw).
#pragma once

#include <cstdint>
#include <exception>
#include <filesystem>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <system_error>

#include <nlohmann/json.hpp>

#include "penumbra/environment.h"
#include "penumbra/gl_context.h"
#include "penumbra/render_job.h"
#include "penumbra/renderer.h"
#include "penumbra/scene.h"

namespace penumbra::web {

namespace fs = std::filesystem;
using nlohmann::json;

// Panoramas are prefiltered on the CPU in the page's only thread: small faces and few samples
// keep that to about a second (docs/web/viewer.md has the measurement).
constexpr int kPanoramaFaceSize = 64;
constexpr int kPanoramaSamples = 32;

struct Viewer {
  std::string selector;
  bool forceHalfFloat = false;
  std::unique_ptr<GlContext> context;
  std::unique_ptr<Renderer> renderer;
  RenderSettings settings;
  std::optional<Scene> scene;
  // Playback's pose (Renderer::setPose): the animation (-1: none, the rest pose) and its time,
  // put back after a lost context.
  int animation = -1;
  float animationTime = 0.0f;
  int variant = -1;    // KHR_materials_variants: the one shown (-1: the default materials)
  Camera sceneCamera;  // the loaded scene's own camera, for reset
  Camera camera;       // the camera in use
  PackedEnvironment environment = uniformEnvironment(glm::vec3(0.0f));
  std::string environmentName = "black";
  bool environmentFromUser = false;  // set through the API, not by a scene file
  // The background apart from the lighting (pv_set_skybox; model-viewer's skybox-image).
  std::optional<PackedEnvironment> skybox;
  std::string skyboxName;
  std::string lastError;
  // A panorama being decoded in steps (pv_env_begin / pv_env_step / pv_env_finish).
  std::optional<PanoramaLoader> pendingPanorama;
  std::string pendingPanoramaName;
  FramePart lastPart;  // what the last pv_step_part did
  Image readback;      // backs the pointer pv_read returns until the next pv_read
};

extern std::unique_ptr<Viewer> gViewer;
extern std::string gResult;  // backs the char* handed to JS until the next call

// The JSON text JS receives (kept in gResult).
const char* finish(const json& j);
json errorJson(const std::string& message);
// The viewer, or why there is none to use (not created, or its WebGL context lost).
Result<Viewer*> viewer();
// The viewer's state (camera, settings, environment, ...), as every call that changes it returns.
json stateJson(const Viewer& v);
EnvironmentLoadOptions panoramaOptions(float sunThreshold);

// Runs `body` (returning json) and turns any escape into {"error": ...}.
template <class F>
const char* guarded(F&& body) {
  try {
    return finish(body());
  } catch (const std::bad_alloc&) {
    return finish(errorJson("out of memory"));
  } catch (const std::exception& e) {
    return finish(errorJson(std::string("internal error: ") + e.what()));
  } catch (...) {
    return finish(errorJson("internal error: unknown exception"));
  }
}

// Makes the staging folder the working directory for one load, so the loaders see the names
// the user knows ("model.glb", "../env/sky.hdr") and their messages say those, not a staging
// path. Restores "/" afterwards.
struct InFolder {
  bool ok = false;
  explicit InFolder(const char* dir) {
    std::error_code ec;
    fs::current_path(dir, ec);
    ok = !ec;
  }
  ~InFolder() {
    std::error_code ec;
    fs::current_path("/", ec);
  }
};

}  // namespace penumbra::web
