// SceneState, one part of Renderer::Impl (render/renderer_impl.h): what is drawn. The scene on
// the GPU, its lights (and the environment's sun and sky samples), the environment and the
// view's background, the camera, and the probe volume's box as the scene file sets it.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/gpu_environment.h"
#include "gpu/gpu_scene.h"
#include "penumbra/animation.h"
#include "penumbra/ibl.h"
#include "penumbra/scene.h"

namespace penumbra {

struct SceneState {
  std::unique_ptr<GpuScene> scene;
  std::shared_ptr<const Rig> rig;  // playback's (Scene::rig; null: a still scene)
  Bounds restBounds;               // the scene's as loaded: the default camera's, not the pose's
  // Some surface of the scene faces another (scene/self_visibility.h): without, the probe
  // volume and the occlusion rays are skipped, as they could only give what is there without.
  bool seesItself = true;
  std::vector<Light> lights;  // the scene's, then the environment's sun if it has one
  std::vector<Light> sceneLights;
  std::optional<ibl::Sun> sun;  // as stored with the environment (unrotated, unscaled)
  ibl::SkyDistribution sky;     // the environment without its sun, for sky shadows
  Light skySample;              // this frame's sky-shadow sample (punctual draws point to it)
  std::unique_ptr<GpuEnvironment> environment;
  std::unique_ptr<GpuEnvironment> skybox;  // the view's background (setSkybox); null: environment
  float environmentMean = 0.0f;            // mean radiance of the environment (before intensity)
  Camera camera;
  bool hasCamera = false;
  Bounds probeBox;              // the scene file's, else the scene's bounds
  glm::ivec3 probeCounts{0};    // the scene file's (0: from the density)

  Camera activeCamera() const { return hasCamera ? camera : defaultCameraForBounds(); }
  Camera defaultCameraForBounds() const {
    Scene empty;
    empty.bounds = restBounds;
    return defaultCamera(empty);
  }
};

}  // namespace penumbra
