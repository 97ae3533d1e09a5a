// The web viewer's environment exports (web/lib/penumbra.mjs calls them; docs/web/viewer.md): a
// file staged in the in-memory file system, a large panorama decoded in steps, a uniform sky and the
// built-in ones. Each returns the viewer's state as JSON, or {error}, as viewer_main.cpp's do.
#include <emscripten/emscripten.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "viewer_state.h"

using namespace penumbra;
using namespace penumbra::web;

namespace {
// An environment file staged in folder `dir` (a packed one, or a panorama prefiltered here with
// the sun threshold in force), for pv_set_environment and pv_set_skybox.
Result<PackedEnvironment> loadStaged(const Viewer& v, const char* dir, const std::string& file) {
  InFolder here(dir);
  if (!here.ok) return makeError(std::string("cannot enter staging folder ") + dir);
  return loadEnvironment(file, panoramaOptions(v.settings.sunThreshold));
}
}  // namespace

extern "C" {

// A packed environment (penumbra-prefilter) or a panorama (.hdr/.png, prefiltered here),
// `file` staged in folder `dir`.
EMSCRIPTEN_KEEPALIVE const char* pv_set_environment(const char* dir, const char* file) {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    const std::string path = file;
    auto env = loadStaged(**v, dir, path);
    if (!env) return errorJson(env.message());
    if (auto st = (*v)->renderer->setEnvironment(*env); !st) return errorJson(st.message());
    (*v)->environment = std::move(*env);
    (*v)->environmentName = fs::path(path).filename().string();
    (*v)->environmentFromUser = true;
    return stateJson(**v);
  });
}

// A large Radiance panorama in steps, so the page is never blocked for long: pv_env_begin
// takes the file's `size` bytes at `data` (copied; not staged as a file: writing and reading
// back 30 MB through the in-memory file system took 3 s) and reads its header ({width,
// height} or {error}); pv_env_step decodes up to `rows` scanlines ({done} or {error});
// pv_env_finish prefilters and sets it, as pv_set_environment does (the state, or {error}). A
// new begin drops one in progress.
EMSCRIPTEN_KEEPALIVE const char* pv_env_begin(const uint8_t* data, int size, const char* file) {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    (*v)->pendingPanorama.reset();
    auto loader = PanoramaLoader::start(std::vector<uint8_t>(data, data + std::max(size, 0)), file,
                                        panoramaOptions((*v)->settings.sunThreshold));
    if (!loader) return errorJson(loader.message());
    (*v)->pendingPanorama = std::move(*loader);
    (*v)->pendingPanoramaName = file;
    return {{"width", (*v)->pendingPanorama->width()}, {"height", (*v)->pendingPanorama->height()}};
  });
}

EMSCRIPTEN_KEEPALIVE const char* pv_env_step(int rows) {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    if (!(*v)->pendingPanorama) return errorJson("no panorama is being loaded");
    if (auto st = (*v)->pendingPanorama->step(rows); !st) {
      (*v)->pendingPanorama.reset();
      return errorJson(st.message());
    }
    return {{"done", (*v)->pendingPanorama->done()}};
  });
}

EMSCRIPTEN_KEEPALIVE const char* pv_env_finish() {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    if (!(*v)->pendingPanorama || !(*v)->pendingPanorama->done()) {
      return errorJson("no decoded panorama to finish");
    }
    auto env = (*v)->pendingPanorama->finish();
    (*v)->pendingPanorama.reset();
    if (!env) return errorJson(env.message());
    if (auto st = (*v)->renderer->setEnvironment(*env); !st) return errorJson(st.message());
    (*v)->environment = std::move(*env);
    (*v)->environmentName = fs::path((*v)->pendingPanoramaName).filename().string();
    (*v)->environmentFromUser = true;
    return stateJson(**v);
  });
}

EMSCRIPTEN_KEEPALIVE const char* pv_set_uniform_environment(float r, float g, float b) {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    PackedEnvironment env = uniformEnvironment(glm::vec3(r, g, b));
    if (auto st = (*v)->renderer->setEnvironment(env); !st) return errorJson(st.message());
    (*v)->environment = std::move(env);
    (*v)->environmentName = "uniform";
    (*v)->environmentFromUser = true;
    return stateJson(**v);
  });
}

// The background apart from the lighting (model-viewer's skybox-image): a packed environment
// or a panorama as pv_set_environment takes, `file` staged in folder `dir`; an empty `file`
// shows the environment again.
EMSCRIPTEN_KEEPALIVE const char* pv_set_skybox(const char* dir, const char* file) {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    const std::string path = file ? file : "";
    if (path.empty()) {
      if (auto st = (*v)->renderer->setSkybox(nullptr); !st) return errorJson(st.message());
      (*v)->skybox.reset();
      (*v)->skyboxName.clear();
      return stateJson(**v);
    }
    auto env = loadStaged(**v, dir, path);
    if (!env) return errorJson(env.message());
    if (auto st = (*v)->renderer->setSkybox(&*env); !st) return errorJson(st.message());
    (*v)->skybox = std::move(*env);
    (*v)->skyboxName = fs::path(path).filename().string();
    return stateJson(**v);
  });
}

// A built-in environment: "studio" (the neutral studio, as a scene file's "studio") stays for
// later bare models like a file set through the API; "default" forgets the API's environment
// and applies the rule (black for a scene with area lights, else the studio), which later
// bare models follow too.
EMSCRIPTEN_KEEPALIVE const char* pv_set_builtin_environment(const char* name) {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    const std::string kind = name ? name : "";
    if (kind != "studio" && kind != "default") {
      return errorJson("unknown built-in environment '" + kind + "' (studio or default)");
    }
    // Without a scene the rule waits for one: loadScene applies it.
    if (kind == "default" && !(*v)->scene) {
      (*v)->environmentFromUser = false;
      return stateJson(**v);
    }
    std::string envName = "studio";
    auto env = kind == "studio" ? studioEnvironment()
                                : resolveEnvironment({.kind = EnvironmentSpec::Kind::Default},
                                                     *(*v)->scene, {}, &envName);
    if (!env) return errorJson(env.message());
    if (auto st = (*v)->renderer->setEnvironment(*env); !st) return errorJson(st.message());
    (*v)->environment = std::move(*env);
    (*v)->environmentName = envName;
    (*v)->environmentFromUser = kind == "studio";
    return stateJson(**v);
  });
}

}  // extern "C"
