// The wasm side of Penumbra's web viewer (web/lib/penumbra.mjs drives it; docs/web/viewer.md).
//
// One module instance serves one canvas. JS fetches files and stages them in the module's
// in-memory file system (pv_write_file), so the renderer's ordinary file loaders resolve a
// .gltf's external buffers and a scene file's glTF and environment exactly as natively. JS owns
// the frame loop: pv_step draws one intermediate frame, pv_sync waits for the GPU (glFinish does
// not block in WebGL), pv_present tone-maps the accumulation into the canvas. pv_step_part
// draws one part of a frame split into bands (pv_set_tiles), for frames too slow for one
// animation frame.
//
// Every export returns plainly (numbers, or JSON text with "error" on failure) inside a
// try/catch: a C++ exception or a Result error must never cross into JS as a throw or an abort.
// The CPU copies of the scene and environment are kept so that a lost WebGL context can be
// rebuilt in full on restore (pv_context_lost / pv_context_restored).
#include <emscripten/emscripten.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include <GLES3/gl3.h>  // only for the 1-pixel read-back of pv_sync
#include "penumbra/environment.h"
#include "penumbra/gl_context.h"
#include "penumbra/render_job.h"
#include "penumbra/renderer.h"
#include "penumbra/scene.h"
#include "viewer_state.h"

namespace penumbra::web {

std::unique_ptr<Viewer> gViewer;
std::string gResult;  // backs the char* handed to JS until the next call

const char* finish(const json& j) {
  // replace: a driver string or a file name with invalid UTF-8 must not make dump() throw.
  gResult = j.dump(-1, ' ', false, json::error_handler_t::replace);
  return gResult.c_str();
}

json errorJson(const std::string& message) {
  return {{"error", message}};
}

json vec3Json(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

json cameraJson(const Camera& c) {
  const float* m = glm::value_ptr(c.world);
  return {{"name", c.name},
          {"world", std::vector<float>(m, m + 16)},  // column-major camera-to-world
          {"eye", vec3Json(glm::vec3(c.world[3]))},
          {"forward", vec3Json(-glm::vec3(c.world[2]))},
          {"up", vec3Json(glm::vec3(c.world[1]))},
          {"yfov", c.yfov},
          {"znear", c.znear},
          {"orthographic", c.orthographic},
          {"ymag", c.ymag}};
}

json stateJson(const Viewer& v) {
  json j = {{"settings", json::parse(settingsToJson(v.settings))},
            {"camera", cameraJson(v.camera)},
            {"environment", v.environmentName},
            {"skybox", v.skybox ? json(v.skyboxName) : json(nullptr)}};
  if (v.scene) {
    j["bounds"] = {{"min", vec3Json(v.scene->bounds.min)}, {"max", vec3Json(v.scene->bounds.max)}};
    j["triangles"] = v.scene->triangleCount();
    json names = json::array();
    for (const Camera& c : v.scene->cameras) names.push_back(c.name);
    j["cameras"] = names;
    j["lights"] = v.scene->lights.size();
    j["variants"] = v.scene->variants;
    json animations = json::array();
    for (const Scene::Animation& a : v.scene->animations) {
      animations.push_back({{"name", a.name}, {"duration", a.duration}});
    }
    j["animations"] = animations;
    j["variant"] =
        v.variant >= 0 ? json(v.scene->variants[static_cast<size_t>(v.variant)]) : json(nullptr);
  }
  return j;
}

// (Re)creates the GL context and renderer and uploads everything the viewer holds. Used at
// start-up and after a lost context is restored (every GL object died with the context).
Status buildGpuState(Viewer& v) {
  v.renderer.reset();
  v.context.reset();
  auto ctx = GlContext::create({.backend = GlBackend::WebGL2, .canvasSelector = v.selector});
  if (!ctx) return ctx.error();
  v.context = std::move(*ctx);
  auto r = Renderer::create({.desktopGl = false, .forceHalfFloat = v.forceHalfFloat});
  if (!r) return r.error();
  v.renderer = std::move(*r);
  PN_TRY(v.renderer->setSettings(v.settings));
  PN_TRY(v.renderer->setEnvironment(v.environment));
  if (v.skybox) PN_TRY(v.renderer->setSkybox(&*v.skybox));
  if (v.scene) {
    PN_TRY(v.renderer->setScene(*v.scene));
    PN_TRY(v.renderer->setVariant(v.variant));
    if (v.animation >= 0) PN_TRY(v.renderer->setPose(v.animation, v.animationTime));
  }
  v.renderer->setCamera(v.camera);
  return {};
}

Result<Viewer*> viewer() {
  if (!gViewer) return makeError("the viewer is not initialised");
  if (!gViewer->renderer) return makeError("the WebGL context is lost (waiting for restore)");
  return gViewer.get();
}

// How the viewer prefilters a panorama, whether set through the API or named by a scene file:
// decoded box-filtered to 16 x 64 = 1024 pixels wide (kPanoramaWidthPerFace), one over
// 8192x4096 refused (web/lib/staging.mjs refuses it before it reaches the heap), with the sun
// threshold in force when the file is loaded (settings.sunThreshold).
constexpr int64_t kMaxPanoramaPixels = int64_t{8192} * 4096;
EnvironmentLoadOptions panoramaOptions(float sunThreshold) {
  return {.faceSize = kPanoramaFaceSize,
          .samples = kPanoramaSamples,
          .sunThreshold = sunThreshold,
          .maxPanoramaPixels = kMaxPanoramaPixels};
}

std::string lowerExtension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

// Loads a scene file (.json), .gltf or .glb staged at `path`, by the same rules as every other
// program (RenderJob). Nothing changes unless every part (model, camera, environment, settings)
// loaded: a bad file leaves the old scene on screen.
json loadScene(Viewer& v, const std::string& path) {
  const bool sceneFile = lowerExtension(path) == ".json";
  // An environment the user chose stays for a bare model; a scene file brings its own.
  const bool keepEnvironment = !sceneFile && v.environmentFromUser;
  JobRequest request;
  request.scenePath = path;
  // The canvas decides the resolution.
  request.settings = {{"width", std::to_string(v.settings.width)},
                      {"height", std::to_string(v.settings.height)}};
  // wasm32 memory tops out at 2 GiB; textures are kept up to what the device takes.
  request.memoryBudgetBytes = int64_t{768} << 20;
  request.maxTextureSize = std::max(1, v.renderer->maxTextureSize());
  request.playback = true;  // the element plays animations (Renderer::setPose)
  request.panorama = panoramaOptions(-1.0f);  // the scene's settings decide the sun
  if (keepEnvironment) request.environment = EnvironmentSpec{.kind = EnvironmentSpec::Kind::None};
  auto job = RenderJob::load(request);
  if (!job) return errorJson(job.message());

  Renderer& r = *v.renderer;
  if (auto st = r.setSettings(job->settings); !st) return errorJson(st.message());
  if (!keepEnvironment) {
    if (auto st = r.setEnvironment(job->environment); !st) return errorJson(st.message());
    v.environment = std::move(job->environment);
    v.environmentName = fs::path(job->environmentName).filename().string();
    v.environmentFromUser = false;
  }
  if (auto st = r.setScene(job->scene); !st) {
    // The GPU upload failed part-way: put the previous scene back so the viewer keeps working.
    if (v.scene) (void)r.setScene(*v.scene);
    (void)r.setSettings(v.settings);
    return errorJson(st.message());
  }
  (void)r.setVariant(job->variant);  // found in this scene by RenderJob: cannot fail
  r.setCamera(job->camera);
  v.settings = job->settings;
  v.variant = job->variant;
  v.animation = -1;
  v.animationTime = 0.0f;
  v.scene = std::move(job->scene);
  v.sceneCamera = job->camera;
  v.camera = job->camera;
  json j = stateJson(v);
  j["warnings"] = job->warnings;
  j["sceneFile"] = sceneFile;
  return j;
}

}  // namespace penumbra::web

using namespace penumbra;
using namespace penumbra::web;

extern "C" {

// Memory for JS to copy file bytes into (the module does not export malloc itself).
EMSCRIPTEN_KEEPALIVE void* pv_alloc(int bytes) {
  return bytes > 0 ? std::malloc(bytes) : nullptr;
}
EMSCRIPTEN_KEEPALIVE void pv_free(void* p) {
  std::free(p);
}

// Creates the WebGL2 context on `selector` and the renderer. Returns {context, report} or
// {error}. Settings start at the renderer's defaults; JS sets the resolution next.
EMSCRIPTEN_KEEPALIVE const char* pv_create(const char* selector, int forceHalfFloat) {
  return guarded([&]() -> json {
    gViewer = std::make_unique<Viewer>();
    gViewer->selector = selector ? selector : "#canvas";
    gViewer->forceHalfFloat = forceHalfFloat != 0;
    if (auto st = buildGpuState(*gViewer); !st) {
      gViewer.reset();
      return errorJson(st.message());
    }
    return {{"context", gViewer->context->description()},
            {"report", gViewer->renderer->capabilityReport()},
            {"state", stateJson(*gViewer)}};
  });
}

EMSCRIPTEN_KEEPALIVE void pv_destroy() {
  try {
    gViewer.reset();
  } catch (...) {
  }
}

// Writes bytes to `path` in the in-memory file system, creating folders.
EMSCRIPTEN_KEEPALIVE const char* pv_write_file(const char* path, const uint8_t* data, int size) {
  return guarded([&]() -> json {
    const fs::path p(path);
    std::error_code ec;
    fs::create_directories(p.parent_path(), ec);
    if (ec) return errorJson("cannot create folder for " + p.string() + ": " + ec.message());
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    if (size > 0) out.write(reinterpret_cast<const char*>(data), size);
    if (!out) return errorJson("cannot write " + p.string());
    return {{"ok", true}};
  });
}

// Removes a staging folder once its files have been loaded (the scene keeps its own copy).
EMSCRIPTEN_KEEPALIVE void pv_remove_tree(const char* path) {
  try {
    std::error_code ec;
    fs::remove_all(path, ec);
  } catch (...) {
  }
}

// Loads `file` (a scene .json, .gltf or .glb) staged in folder `dir`.
EMSCRIPTEN_KEEPALIVE const char* pv_load_scene(const char* dir, const char* file) {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    InFolder here(dir);
    if (!here.ok) return errorJson(std::string("cannot enter staging folder ") + dir);
    return loadScene(**v, file);
  });
}

// Merges a JSON object of settings (keys of the settings schema, penumbra/settings.h) into the
// current ones. The JS API passes only the keys the schema marks for the viewer; the canvas
// size arrives here as width and height.
EMSCRIPTEN_KEEPALIVE const char* pv_set_settings(const char* changes) {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    auto merged = mergeSettingsJson((*v)->settings, changes ? changes : "");
    if (!merged) return errorJson(merged.message());
    if (auto st = (*v)->renderer->setSettings(*merged); !st) return errorJson(st.message());
    (*v)->settings = *merged;
    return json::parse(settingsToJson((*v)->settings));
  });
}

// The settings schema: [{key, type, min, max, default, help, viewer, range}, ...]. The JS API
// derives the keys setSettings() accepts from it.
EMSCRIPTEN_KEEPALIVE const char* pv_settings_schema() {
  return guarded([&]() -> json { return json{{"settings", json::parse(settingsSchemaJson())}}; });
}

EMSCRIPTEN_KEEPALIVE const char* pv_get_state() {
  return guarded([&]() -> json {
    if (!gViewer) return errorJson("the viewer is not initialised");
    return stateJson(*gViewer);
  });
}

// Shows a KHR_materials_variants variant by name or index ("" or "default": the primitives'
// own materials); restarts accumulation.
EMSCRIPTEN_KEEPALIVE const char* pv_set_variant(const char* nameOrIndex) {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    if (!(*v)->scene) return errorJson("setVariant: no scene loaded");
    auto index = findVariant(*(*v)->scene, nameOrIndex ? nameOrIndex : "");
    if (!index) return errorJson(index.message());
    if (auto st = (*v)->renderer->setVariant(*index); !st) return errorJson(st.message());
    (*v)->variant = *index;
    return stateJson(**v);
  });
}

// Playback: poses the scene at `time` seconds of animation `index` (-1: the rest pose) on the
// GPU, blended with animation `from` at `fromTime` by `fromWeight` while a crossfade runs (0:
// none); restarts accumulation (a playing animation is a moving view).
EMSCRIPTEN_KEEPALIVE const char* pv_set_pose(int index, float time, int from, float fromTime,
                                             float fromWeight) {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    if (!(*v)->scene) return errorJson("setPose: no scene loaded");
    PoseLayer layers[2] = {{index, time, 1.0f}, {from, fromTime, fromWeight}};
    size_t count = 1;
    if (fromWeight > 0.0f) {
      layers[0].weight = 1.0f - fromWeight;
      count = 2;
    }
    auto st = (*v)->renderer->setPose(std::span<const PoseLayer>(layers, count));
    if (!st) return errorJson(st.message());
    (*v)->animation = index;
    (*v)->animationTime = time;
    return json{{"animation", index}, {"time", time}};
  });
}

// A look-at camera (the orbit controls). yfov in radians; znear from the scene's bounds so the
// depth range fits wherever the orbit goes.
EMSCRIPTEN_KEEPALIVE const char* pv_set_camera(float ex, float ey, float ez, float tx, float ty,
                                               float tz, float ux, float uy, float uz, float yfov) {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    const glm::vec3 eye(ex, ey, ez), target(tx, ty, tz), up(ux, uy, uz);
    const glm::vec3 dir = target - eye;
    if (!(glm::length(dir) > 1e-6f) || !(glm::length(glm::cross(dir, up)) > 1e-9f) ||
        !(yfov > 0.0f && yfov < 3.1f) || !std::isfinite(ex + ey + ez + tx + ty + tz)) {
      return errorJson(
          "camera: eye and target must differ, up must not be parallel to the view, "
          "and yfov must be in (0, 3.1) radians");
    }
    Camera c;
    c.name = "orbit";
    c.world = glm::inverse(glm::lookAt(eye, target, up));
    c.yfov = yfov;
    // Fit as the scene's camera does, so the first drag does not change the framing.
    c.aspect = (*v)->sceneCamera.aspect > 0.0f ? (*v)->sceneCamera.aspect : 1.0f;
    float dist = glm::length(dir), radius = 1.0f;
    if ((*v)->scene && (*v)->scene->bounds.valid()) {
      dist = glm::length((*v)->scene->bounds.center() - eye);
      radius = (*v)->scene->bounds.radius();
    }
    c.znear = std::max(std::max(dist - radius, dist * 0.01f) * 0.5f, 1e-4f);
    (*v)->camera = c;
    (*v)->renderer->setCamera(c);
    return cameraJson(c);
  });
}

// Back to the loaded scene's own camera, exactly (no look-at round trip).
EMSCRIPTEN_KEEPALIVE const char* pv_reset_camera() {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    (*v)->camera = (*v)->sceneCamera;
    (*v)->renderer->setCamera((*v)->camera);
    return cameraJson((*v)->camera);
  });
}

// Draws the next intermediate frame: its number, 0 once converged, -1 on error (pv_last_error).
EMSCRIPTEN_KEEPALIVE int pv_step() {
  try {
    auto v = viewer();
    if (!v) {
      if (gViewer) gViewer->lastError = v.message();
      return -1;
    }
    auto f = (*v)->renderer->step();
    if (!f) {
      (*v)->lastError = f.message();
      return -1;
    }
    return *f;
  } catch (const std::exception& e) {
    if (gViewer) gViewer->lastError = std::string("internal error: ") + e.what();
  } catch (...) {
    if (gViewer) gViewer->lastError = "internal error: unknown exception";
  }
  return -1;
}

// Draws the next part of the next frame (Renderer::stepPart): 1 when that completed the frame,
// 2 when the frame has parts left, 0 once converged, -1 on error (pv_last_error).
EMSCRIPTEN_KEEPALIVE int pv_step_part() {
  try {
    auto v = viewer();
    if (!v) {
      if (gViewer) gViewer->lastError = v.message();
      return -1;
    }
    auto p = (*v)->renderer->stepPart();
    if (!p) {
      (*v)->lastError = p.message();
      return -1;
    }
    (*v)->lastPart = *p;
    return p->frame == 0 ? 0 : p->done ? 1 : 2;
  } catch (const std::exception& e) {
    if (gViewer) gViewer->lastError = std::string("internal error: ") + e.what();
  } catch (...) {
    if (gViewer) gViewer->lastError = "internal error: unknown exception";
  }
  return -1;
}

// Bands of the frames pv_step_part begins from now on; returns the count in effect (clamped to
// 1..64), 0 without a renderer.
EMSCRIPTEN_KEEPALIVE int pv_set_tiles(int tiles) {
  if (!gViewer || !gViewer->renderer) return 0;
  gViewer->renderer->setFrameTiles(tiles);
  return gViewer->renderer->frameTiles();
}

// Which part (1-based; 1: the frame began with it) of how many parts the last pv_step_part drew.
EMSCRIPTEN_KEEPALIVE int pv_last_part() {
  return gViewer ? gViewer->lastPart.part : 0;
}
EMSCRIPTEN_KEEPALIVE int pv_last_parts() {
  return gViewer ? gViewer->lastPart.parts : 0;
}

EMSCRIPTEN_KEEPALIVE const char* pv_last_error() {
  return guarded([&]() -> json { return gViewer ? gViewer->lastError : std::string(); });
}

// Waits until the GPU has executed everything issued so far: glFinish does not block in WebGL,
// but a 1-pixel readPixels does (Chromium runs the GPU command stream in order and the read is
// a synchronous round trip), so the JS frame loop can time frames against its budget.
EMSCRIPTEN_KEEPALIVE void pv_sync() {
  if (!gViewer || !gViewer->renderer) return;
  uint8_t px[4];
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
}

// Tone-maps the accumulated image into the canvas (width x height, its drawing-buffer size).
EMSCRIPTEN_KEEPALIVE const char* pv_present(int width, int height) {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    if (auto st = (*v)->renderer->present(width, height); !st) return errorJson(st.message());
    return {{"ok", true}};
  });
}

// The running mean of linear radiance before exposure (display = 0) or the displayed image
// (display = 1: exposure, tone mapping and sRGB, in [0, 1]), RGBA float at the render size, row 0
// at the top: {width, height, frames, ptr} with ptr into the wasm heap, valid until the next
// pv_read; or {error}. The images of the last complete frame, as present() shows it.
EMSCRIPTEN_KEEPALIVE const char* pv_read(int display) {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    Renderer& r = *(*v)->renderer;
    auto img = display ? r.readDisplay() : r.readRadiance();
    if (!img) return errorJson(img.message());
    if (img->channels != 4) return errorJson("read-back: expected an RGBA image");
    (*v)->readback = std::move(*img);
    const Image& out = (*v)->readback;
    return {{"width", out.width},
            {"height", out.height},
            {"frames", r.framesDone()},
            {"ptr", reinterpret_cast<uintptr_t>(out.pixels.data())}};
  });
}

EMSCRIPTEN_KEEPALIVE int pv_frames_done() {
  return gViewer && gViewer->renderer ? gViewer->renderer->framesDone() : 0;
}
// m, or an automatic view's expected frames (its measured estimate; its frame once converged).
EMSCRIPTEN_KEEPALIVE int pv_total_frames() {
  return gViewer && gViewer->renderer ? gViewer->renderer->convergence().expectedFrames : 0;
}
// The GPU memory the renderer's textures, renderbuffers and buffers hold
// (Renderer::gpuMemoryBytes; a double: wasm32's int would cap it at 2 GiB).
EMSCRIPTEN_KEEPALIVE double pv_gpu_memory() {
  return static_cast<double>(Renderer::gpuMemoryBytes());
}
EMSCRIPTEN_KEEPALIVE int pv_converged() {
  return gViewer && gViewer->renderer && gViewer->renderer->converged() ? 1 : 0;
}
// The first picture of a view: frame 1 at the preview's scale (a quarter of the pixels),
// upsampled into the image and shown; not part of the mean (Renderer::preview).
EMSCRIPTEN_KEEPALIVE const char* pv_preview() {
  return guarded([&]() -> json {
    auto v = viewer();
    if (!v) return errorJson(v.message());
    if (auto st = (*v)->renderer->preview(); !st) return errorJson(st.message());
    return {{"ok", true}};
  });
}
EMSCRIPTEN_KEEPALIVE void pv_restart() {
  if (gViewer && gViewer->renderer) gViewer->renderer->restart();
}

// The canvas lost its WebGL context: drop every GL object (their deletes are no-ops on a lost
// context) but keep the scene, environment, camera and settings for the restore.
EMSCRIPTEN_KEEPALIVE void pv_context_lost() {
  try {
    if (!gViewer) return;
    gViewer->renderer.reset();
    gViewer->context.reset();
  } catch (...) {
  }
}

// The context is back: recreate context, renderer and all uploads. {state} or {error}.
EMSCRIPTEN_KEEPALIVE const char* pv_context_restored() {
  return guarded([&]() -> json {
    if (!gViewer) return errorJson("the viewer is not initialised");
    if (auto st = buildGpuState(*gViewer); !st) {
      gViewer->renderer.reset();
      return errorJson("restoring after context loss: " + st.message());
    }
    return {{"context", gViewer->context->description()},
            {"report", gViewer->renderer->capabilityReport()},
            {"state", stateJson(*gViewer)}};
  });
}

}  // extern "C"
