// View and projection matrices of a scene camera for a viewport, with a sub-pixel jitter.
// The viewport's aspect ratio wins over the camera's (the vertical field of view, or an
// orthographic camera's height, is kept).
#pragma once

#include <glm/glm.hpp>

#include "penumbra/scene.h"

namespace penumbra {

struct CameraMatrices {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  glm::vec3 position{0.0f};
  // Where shading looks from: (camera position, 1) for a perspective camera, (the direction
  // back toward the viewer, 0) for an orthographic one, whose view rays are parallel.
  glm::vec4 viewOrigin{0.0f, 0.0f, 0.0f, 1.0f};
};

// jitter is in pixels; it shifts the whole image by that amount.
CameraMatrices cameraMatrices(const Camera& camera, int width, int height, glm::vec2 jitter);

}  // namespace penumbra
