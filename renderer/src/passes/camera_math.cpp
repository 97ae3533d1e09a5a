#include "passes/camera_math.h"

#include <algorithm>
#include <cmath>

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
  const glm::vec2 offset = 2.0f * jitter / glm::vec2(width, std::max(height, 1));
  // Fit: a viewport wider than the camera's own aspect shows more at the sides (the vertical
  // extent is kept); a narrower one keeps the horizontal extent and shows more above and
  // below, so a portrait screen still shows the whole frame (Blender's automatic sensor fit).
  const float fit = camera.aspect > 0.0f && aspect < camera.aspect ? camera.aspect / aspect : 1.0f;
  if (camera.orthographic) {
    const float h = camera.ymag * fit, w = h * aspect;
    // An orthographic frustum needs a finite far plane; a camera built in code may leave it 0.
    const float znear = std::max(camera.znear, 0.0f);
    const float zfar = camera.zfar > znear ? camera.zfar : znear + 1.0e4f;
    m.projection = glm::ortho(-w, w, -h, h, znear, zfar);
    // w = 1: the offset goes into the translation, with the same sign as below.
    m.projection[3][0] -= offset.x;
    m.projection[3][1] -= offset.y;
    m.viewOrigin = glm::vec4(glm::vec3(world[2]), 0.0f);
    return m;
  }
  const float znear = camera.znear > 0.0f ? camera.znear : 0.01f;
  const float yfov = 2.0f * std::atan(std::tan(0.5f * camera.yfov) * fit);
  m.projection = camera.zfar > znear ? glm::perspective(yfov, aspect, znear, camera.zfar)
                                     : glm::infinitePerspective(yfov, aspect, znear);
  // A clip-space offset of 2 * pixels / size moves the image by `pixels`.
  m.projection[2][0] += offset.x;
  m.projection[2][1] += offset.y;
  m.viewOrigin = glm::vec4(m.position, 1.0f);
  return m;
}

}  // namespace penumbra
