#include "render/camera_math.h"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

namespace penumbra {

CameraMatrices cameraMatrices(const Camera& camera, int width, int height, glm::vec2 jitter) {
  CameraMatrices m;
  // Remove scale from the camera's world matrix: only its rigid part defines the view.
  glm::mat4 world = camera.world;
  for (int i = 0; i < 3; ++i) {
    const float len = glm::length(glm::vec3(world[i]));
    if (len > 0.0f) world[i] /= len;
  }
  m.position = glm::vec3(world[3]);
  m.view = glm::inverse(world);
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(height, 1));
  const float znear = camera.znear > 0.0f ? camera.znear : 0.01f;
  m.projection = camera.zfar > znear ? glm::perspective(camera.yfov, aspect, znear, camera.zfar)
                                     : glm::infinitePerspective(camera.yfov, aspect, znear);
  // A clip-space offset of 2 * pixels / size moves the image by `pixels`.
  m.projection[2][0] += 2.0f * jitter.x / static_cast<float>(width);
  m.projection[2][1] += 2.0f * jitter.y / static_cast<float>(height);
  return m;
}

}  // namespace penumbra
