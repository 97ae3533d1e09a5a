#include "render/light_samples.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "progressive/sequences.h"
#include "scene/light_kinds.h"

namespace penumbra::render {

namespace {

// A directional light arriving from `towards` (a direction in the environment's frame), turned
// and scaled like the environment.
Light environmentLight(const char* name, const glm::vec3& towards, const glm::vec3& color,
                       const RenderSettings& settings) {
  const glm::mat3 turn(
      glm::rotate(glm::mat4(1.0f), glm::radians(settings.environmentRotation), glm::vec3(0, 1, 0)));
  Light l;
  l.name = name;
  l.type = LightType::Directional;
  l.direction = -glm::normalize(turn * towards);
  l.color = color;
  l.intensity = settings.environmentIntensity;
  return l;
}

}  // namespace

Light sunLight(const ibl::Sun& sun, const RenderSettings& settings) {
  Light l = environmentLight("environment sun", sun.direction, sun.irradiance, settings);
  l.angularDiameter = 2.0f * sun.angularRadius;
  return l;
}

Light skyLight(const ibl::SkySample& sample, const RenderSettings& settings) {
  return environmentLight("sky shadow sample", sample.direction,
                          sample.pdf > 0.0f ? sample.radiance / sample.pdf : glm::vec3(0.0f),
                          settings);
}

glm::vec3 punctualDirection(const Light& l, glm::vec2 u, const RenderSettings& settings) {
  if (l.type != LightType::Directional) return l.direction;
  const float diameter = l.angularDiameter > 0.0f
                             ? l.angularDiameter
                             : glm::radians(settings.progressive.directionalAngle);
  const float radius = std::tan(0.5f * diameter);
  const glm::vec3 d = glm::normalize(l.direction);
  const glm::vec3 a = std::abs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 right = glm::normalize(glm::cross(a, d)), up = glm::cross(d, right);
  const glm::vec2 p = progressive::concentricDisk(u) * radius;
  return glm::normalize(d + p.x * right + p.y * up);
}

glm::vec3 samplePosition(const Light& l, glm::vec2 u) {
  return lightKind(l.type).samplePoint(l, u);
}

std::vector<passes::CaptureLight> captureLights(const std::vector<Light>& lights, glm::vec2 u,
                                                const RenderSettings& settings) {
  std::vector<passes::CaptureLight> out;
  out.reserve(lights.size());
  for (const Light& l : lights) {
    out.push_back({&l, samplePosition(l, u), punctualDirection(l, u, settings)});
  }
  return out;
}

}  // namespace penumbra::render
