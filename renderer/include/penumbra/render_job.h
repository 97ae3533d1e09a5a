// RenderJob: the application layer's single way of turning what a user asks for (a scene file
// or a glTF, overrides from a command line or an API, a memory budget) into what a Renderer
// needs: the scene, the camera, the environment and the settings. Every program uses it
// (penumbra-render, -bench, -soak, the web viewer, the tests), so the rules and the one-line
// errors are the same everywhere:
//  - settings: the scene file's, then the request's overrides (schema keys), then validated;
//  - camera: the request's, else the scene file's, else the glTF's first, else a framing of the
//    scene's bounds; a name or index that does not exist is an error (so is a variant);
//  - environment: the request's, else the scene file's, else by rule: black when the scene
//    has lights of its own, the neutral studio environment when it has none;
//  - memory: the decoded scene and, separately, the render targets' estimated GPU memory must
//    each fit the budget.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "penumbra/environment.h"
#include "penumbra/environment_format.h"
#include "penumbra/error.h"
#include "penumbra/renderer.h"
#include "penumbra/scene.h"
#include "penumbra/scene_file.h"
#include "penumbra/settings.h"

namespace penumbra {

// Environments already loaded or prefiltered, by what made them (the resolved spec; for a file
// its path, size, time and the prefilter options): a batch of jobs that share a panorama
// prefilters it once. Holds the newest `capacity` entries. Not thread-safe.
class EnvironmentCache {
 public:
  struct Entry {
    PackedEnvironment environment;
    std::string name;
    std::vector<std::string> warnings;  // what loading it warned about, repeated on each hit
  };
  explicit EnvironmentCache(size_t capacity = 4) : capacity_(capacity) {}
  const Entry* find(const std::string& key) const;
  void put(const std::string& key, Entry entry);
  size_t size() const { return entries_.size(); }

 private:
  size_t capacity_;
  std::vector<std::pair<std::string, Entry>> entries_;  // oldest first
};

struct JobRequest {
  std::string scenePath;  // a scene file (.json) or a model (.gltf/.glb)
  // Settings over the scene file's, as (schema key, text) pairs: {"frames", "64"}.
  std::vector<std::pair<std::string, std::string>> settings;
  std::string camera;   // name or index; empty: see above
  std::string variant;  // KHR_materials_variants name or index; empty: the scene file's
  // A glTF animation (name or index) and the time (s) to pose it at; over the scene file's.
  std::string animation;
  std::optional<float> time;
  // Keep what plays the animations back (LoadOptions::playback): a viewer's Renderer::setPose.
  bool playback = false;
  std::optional<EnvironmentSpec> environment;  // replaces the scene file's
  int64_t memoryBudgetBytes = int64_t{2} << 30;
  int maxTextureSize = 4096;
  EnvironmentLoadOptions panorama;           // how panoramas are prefiltered on load
  EnvironmentCache* environments = nullptr;  // reused and filled when given
};

struct RenderJob {
  SceneFile sceneFile;  // as read (before the request's overrides)
  Scene scene;
  Camera camera;
  int variant = -1;  // KHR_materials_variants index; -1: the primitives' own materials
  PackedEnvironment environment;
  std::string environmentName;  // "none", "studio", "uniform(r, g, b)" or the file name
  // What made the environment (EnvironmentCache's key): equal keys, equal environments.
  std::string environmentKey;
  RenderSettings settings;
  std::vector<std::string> warnings;  // the scene file's, then the glTF's

  static Result<RenderJob> load(const JobRequest& request);
  // Sets settings, scene (and variant), environment and camera on a renderer. With
  // `environmentOnGpu` (the environmentKey of what the renderer holds, kept by the caller
  // across jobs) an equal environment is not uploaded again.
  Status applyTo(Renderer& renderer, std::string* environmentOnGpu = nullptr) const;
};

// Settings over a base, as the request's overrides are applied (schema keys and text).
Result<RenderSettings> applySettingOverrides(
    RenderSettings base, const std::vector<std::pair<std::string, std::string>>& overrides);
// Resolves an environment spec for a scene (Kind::Default by the rule above).
Result<PackedEnvironment> resolveEnvironment(const EnvironmentSpec& spec, const Scene& scene,
                                             const EnvironmentLoadOptions& panorama,
                                             std::string* name = nullptr);
// The EnvironmentCache key of a spec resolved for a scene; empty when it cannot be known (a
// file that cannot be read: loading it reports why).
std::string environmentCacheKey(const EnvironmentSpec& spec, const Scene& scene,
                                const EnvironmentLoadOptions& panorama);
// Estimated GPU memory of the render targets for these settings, and the budget check.
int64_t estimateTargetBytes(const RenderSettings& settings);
Status checkTargetBudget(const RenderSettings& settings, int64_t budgetBytes);

}  // namespace penumbra
