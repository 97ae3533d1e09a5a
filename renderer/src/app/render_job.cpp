#include "penumbra/render_job.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

namespace penumbra {

const EnvironmentCache::Entry* EnvironmentCache::find(const std::string& key) const {
  for (const auto& [k, entry] : entries_) {
    if (k == key) return &entry;
  }
  return nullptr;
}

void EnvironmentCache::put(const std::string& key, Entry entry) {
  std::erase_if(entries_, [&](const auto& e) { return e.first == key; });
  entries_.emplace_back(key, std::move(entry));
  while (entries_.size() > capacity_) entries_.erase(entries_.begin());
}

namespace {

// Kind::Default by the rule: black for a scene with area lights (an authored, lit interior),
// else the studio, on top of any punctual lights the file carries (as three.js's and
// model-viewer's viewers light product files; docs/gltf-support.md, "Lights").
EnvironmentSpec::Kind resolvedKind(const EnvironmentSpec& spec, const Scene& scene) {
  using Kind = EnvironmentSpec::Kind;
  if (spec.kind != Kind::Default) return spec.kind;
  const bool areaLit = std::any_of(scene.lights.begin(), scene.lights.end(),
                                   [](const Light& l) { return l.isArea(); });
  return areaLit ? Kind::None : Kind::Studio;
}

}  // namespace

std::string environmentCacheKey(const EnvironmentSpec& spec, const Scene& scene,
                                const EnvironmentLoadOptions& panorama) {
  using Kind = EnvironmentSpec::Kind;
  const Kind kind = resolvedKind(spec, scene);
  char buf[160];
  switch (kind) {
    case Kind::None:
    case Kind::Default:
      return "none";
    case Kind::Studio:
      return "studio";
    case Kind::Uniform:
      std::snprintf(buf, sizeof buf, "uniform %a %a %a", spec.radiance.r, spec.radiance.g,
                    spec.radiance.b);
      return buf;
    case Kind::File: {
      namespace fs = std::filesystem;
      std::error_code ec;
      const fs::path path = fs::absolute(spec.path, ec);
      const auto size = fs::file_size(path, ec);
      if (ec) return {};
      const auto time = fs::last_write_time(path, ec);
      if (ec) return {};
      std::snprintf(buf, sizeof buf, " %ju %lld %d %d %a", static_cast<uintmax_t>(size),
                    static_cast<long long>(time.time_since_epoch().count()), panorama.faceSize,
                    panorama.samples, panorama.sunThreshold);
      return "file " + path.string() + buf;
    }
  }
  return {};
}

Result<RenderSettings> applySettingOverrides(
    RenderSettings s, const std::vector<std::pair<std::string, std::string>>& overrides) {
  for (const auto& [key, text] : overrides) {
    const SettingInfo* info = findSetting(key);
    if (!info) return makeError("unknown setting '" + key + "'");
    PN_TRY(setSettingText(s, *info, text));
  }
  PN_TRY(validate(s));
  return s;
}

Result<PackedEnvironment> resolveEnvironment(const EnvironmentSpec& spec, const Scene& scene,
                                             const EnvironmentLoadOptions& panorama,
                                             std::string* name) {
  using Kind = EnvironmentSpec::Kind;
  const Kind kind = resolvedKind(spec, scene);
  std::string label;
  Result<PackedEnvironment> env = makeError("no environment");
  switch (kind) {
    case Kind::None:
    case Kind::Default:
      env = uniformEnvironment(glm::vec3(0.0f));
      label = "none";
      break;
    case Kind::Studio:
      env = studioEnvironment();
      label = "studio";
      break;
    case Kind::Uniform: {
      env = uniformEnvironment(spec.radiance);
      char buf[96];
      std::snprintf(buf, sizeof buf, "uniform(%g, %g, %g)", spec.radiance.r, spec.radiance.g,
                    spec.radiance.b);
      label = buf;
      break;
    }
    case Kind::File:
      env = loadEnvironment(spec.path, panorama);
      label = spec.path;
      break;
  }
  if (env && name) *name = label;
  return env;
}

int64_t estimateTargetBytes(const RenderSettings& s) {
  // About 5 RGBA32F colour targets and 2 32-bit depth buffers per pixel, the per-view caches
  // (probe lookups, up to 4 area lights: 6 RGBA16F), plus up to 4 shadow maps of 32-bit depth.
  const int64_t pixels = int64_t{s.width} * s.height;
  const int64_t shadow = int64_t{s.progressive.shadowMapSize} * s.progressive.shadowMapSize;
  return pixels * (5 * 16 + 6 * 8 + 2 * 4) + 4 * shadow * 4;
}

Status checkTargetBudget(const RenderSettings& s, int64_t budgetBytes) {
  const int64_t need = estimateTargetBytes(s);
  if (need <= budgetBytes) return {};
  return makeError("render targets for " + std::to_string(s.width) + "x" +
                   std::to_string(s.height) + " need about " + std::to_string(need >> 20) +
                   " MB of GPU memory, over the memory budget of " +
                   std::to_string(budgetBytes >> 20) + " MB");
}

Result<RenderJob> RenderJob::load(const JobRequest& request) {
  if (request.memoryBudgetBytes < 1) {
    return makeError("the memory budget must be a positive number of bytes");
  }
  RenderJob job;
  auto sf = loadSceneFile(request.scenePath);
  if (!sf) return sf.error();
  job.sceneFile = std::move(*sf);
  job.warnings = job.sceneFile.warnings;
  auto settings = applySettingOverrides(job.sceneFile.settings, request.settings);
  if (!settings) return settings.error();
  job.settings = *settings;
  // Refused before anything is decoded or allocated.
  PN_TRY(checkTargetBudget(job.settings, request.memoryBudgetBytes));

  LoadOptions lo;
  lo.memoryBudgetBytes = request.memoryBudgetBytes;
  lo.maxTextureSize = request.maxTextureSize;
  lo.playback = request.playback;
  lo.animation = !request.animation.empty() ? request.animation : job.sceneFile.animation;
  const std::optional<float> time = request.time ? request.time : job.sceneFile.time;
  if (lo.animation.empty() && time) lo.animation.assign(1, '0');  // a time alone: the first one
  lo.animationTime = time.value_or(0.0f);
  auto scene = loadGltf(job.sceneFile.gltfPath, lo);
  if (!scene) return scene.error();
  job.scene = std::move(*scene);
  if (job.sceneFile.probeVolume.hasBox) {
    job.scene.probeBox.min = job.sceneFile.probeVolume.min;
    job.scene.probeBox.max = job.sceneFile.probeVolume.max;
  }
  job.scene.probeCounts = job.sceneFile.probeVolume.counts;
  job.warnings.insert(job.warnings.end(), job.scene.warnings.begin(), job.scene.warnings.end());
  const auto punctual = std::count_if(job.scene.lights.begin(), job.scene.lights.end(),
                                      [](const Light& l) { return !l.isArea(); });
  if (punctual > kMaxPunctualLights) {
    job.warnings.push_back(std::to_string(punctual) + " punctual lights: only the first " +
                           std::to_string(kMaxPunctualLights) + " are shaded");
  }

  const std::string& cameraName = !request.camera.empty() ? request.camera : job.sceneFile.camera;
  if (!cameraName.empty()) {
    auto idx = findCamera(job.scene, cameraName);
    if (!idx) return idx.error();
    job.camera = job.scene.cameras[static_cast<size_t>(*idx)];
  } else if (!job.scene.cameras.empty()) {
    job.camera = job.scene.cameras[0];
  } else {
    const float aspect = static_cast<float>(job.settings.width) /
                         static_cast<float>(std::max(job.settings.height, 1));
    job.camera = defaultCamera(job.scene, aspect);
    if (!lo.animation.empty()) {
      // Framed at rest, as a viewer frames a model once at load: every time of an animation
      // sequence gets the same camera, not one that follows the pose's bounds.
      LoadOptions rest = lo;
      rest.animation.clear();
      if (auto atRest = loadGltf(job.sceneFile.gltfPath, rest))
        job.camera = defaultCamera(*atRest, aspect);
    }
  }

  const std::string& variantName =
      !request.variant.empty() ? request.variant : job.sceneFile.variant;
  auto variant = findVariant(job.scene, variantName);
  if (!variant) return variant.error();
  job.variant = *variant;

  const EnvironmentSpec spec = request.environment.value_or(job.sceneFile.environment);
  EnvironmentLoadOptions panorama = request.panorama;
  panorama.warnings = &job.warnings;
  panorama.sunThreshold = job.settings.sunThreshold;
  job.environmentKey = environmentCacheKey(spec, job.scene, panorama);
  EnvironmentCache* cache = job.environmentKey.empty() ? nullptr : request.environments;
  if (const EnvironmentCache::Entry* hit = cache ? cache->find(job.environmentKey) : nullptr) {
    job.environment = hit->environment;
    job.environmentName = hit->name;
    job.warnings.insert(job.warnings.end(), hit->warnings.begin(), hit->warnings.end());
    return job;
  }
  const size_t warningsBefore = job.warnings.size();
  auto env = resolveEnvironment(spec, job.scene, panorama, &job.environmentName);
  if (!env) return env.error();
  job.environment = std::move(*env);
  if (cache) {
    cache->put(job.environmentKey,
               {job.environment, job.environmentName,
                std::vector<std::string>(job.warnings.begin() + static_cast<long>(warningsBefore),
                                         job.warnings.end())});
  }
  return job;
}

Status RenderJob::applyTo(Renderer& r, std::string* environmentOnGpu) const {
  PN_TRY(r.setSettings(settings));
  PN_TRY(r.setScene(scene));
  PN_TRY(r.setVariant(variant));
  const bool same =
      environmentOnGpu && !environmentKey.empty() && *environmentOnGpu == environmentKey;
  if (!same) {
    if (environmentOnGpu) environmentOnGpu->clear();  // unknown until the upload succeeds
    PN_TRY(r.setEnvironment(environment));
    if (environmentOnGpu) *environmentOnGpu = environmentKey;
  }
  r.setCamera(camera);
  return {};
}

}  // namespace penumbra
