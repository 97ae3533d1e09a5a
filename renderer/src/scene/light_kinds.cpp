#include "scene/light_kinds.h"

#include "penumbra/error.h"

#include <array>

namespace penumbra {
namespace {

float noArea(const Light&) {
  return 0.0f;
}
glm::vec3 atPosition(const Light& l, glm::vec2) {
  return l.position;
}

float rectArea(const Light& l) {
  return l.width * l.height;
}
glm::vec3 onRect(const Light& l, glm::vec2 u) {
  return l.position + (u.x - 0.5f) * l.width * l.right + (u.y - 0.5f) * l.height * l.up;
}

float diskArea(const Light& l) {
  return 0.785398163f * l.width * l.width;  // width is the diameter
}
glm::vec3 onDisk(const Light& l, glm::vec2 u) {
  const glm::vec2 d = progressive::concentricDisk(u) * (0.5f * l.width);
  return l.position + d.x * l.right + d.y * l.up;
}

using progressive::LightShape;
// Indexed by LightType. Shader codes: area shapes 0 rect, 1 disk; punctual 0 point, 1 spot,
// 2 directional.
constexpr std::array<LightKind, 5> kKinds = {{
    {LightType::Rect, "rect", true, LightShape::Rect, ShadowProjection::Perspective, 0, rectArea,
     onRect},
    {LightType::Disk, "disk", true, LightShape::Disk, ShadowProjection::Perspective, 1, diskArea,
     onDisk},
    {LightType::Point, "point", false, LightShape::Point, ShadowProjection::Cube, 0, noArea,
     atPosition},
    {LightType::Spot, "spot", false, LightShape::Point, ShadowProjection::Perspective, 1, noArea,
     atPosition},
    {LightType::Directional, "directional", false, LightShape::Disk, ShadowProjection::Orthographic,
     2, noArea, atPosition},
}};

constexpr bool inOrder() {
  for (size_t i = 0; i < kKinds.size(); ++i) {
    if (static_cast<size_t>(kKinds[i].type) != i) return false;
  }
  return true;
}
static_assert(inOrder(), "kKinds is indexed by LightType");

constexpr std::array<PunctualSampleKind, static_cast<size_t>(PunctualSample::Count)> kSamples = {{
    {PunctualSample::Point, "point"},
    {PunctualSample::Spot, "spot"},
    {PunctualSample::Directional, "directional"},
    {PunctualSample::Sun, "sun"},
    {PunctualSample::SkyShadow, "sky-shadow"},
}};

constexpr bool samplesInOrder() {
  for (size_t i = 0; i < kSamples.size(); ++i) {
    if (static_cast<size_t>(kSamples[i].sample) != i) return false;
  }
  // A punctual light's shader code is its plain sample's.
  for (const LightKind& k : kKinds) {
    if (k.area) continue;
    const PunctualSample plain = k.type == LightType::Point  ? PunctualSample::Point
                                 : k.type == LightType::Spot ? PunctualSample::Spot
                                                             : PunctualSample::Directional;
    if (k.shaderCode != static_cast<int>(plain)) return false;
  }
  return true;
}
static_assert(samplesInOrder(), "kSamples is indexed by PunctualSample; lights' codes match");

}  // namespace

const LightKind& lightKind(LightType type) {
  return kKinds[static_cast<size_t>(type)];
}

std::span<const LightKind> lightKinds() {
  return kKinds;
}

std::span<const PunctualSampleKind> punctualSampleKinds() {
  return kSamples;
}

PunctualSample punctualSample(const Light& light, bool sun, bool skyShadow) {
  if (skyShadow) return PunctualSample::SkyShadow;
  const LightKind& k = lightKind(light.type);
  PN_CHECK(!k.area, "punctualSample: a punctual light");
  const auto plain = static_cast<PunctualSample>(k.shaderCode);
  return plain == PunctualSample::Directional && sun ? PunctualSample::Sun : plain;
}

const LightKind* lightKindNamed(std::string_view name, bool area) {
  for (const LightKind& k : kKinds) {
    if (k.area == area && name == k.name) return &k;
  }
  return nullptr;
}

bool Light::isArea() const {
  return lightKind(type).area;
}

float Light::area() const {
  return lightKind(type).surfaceArea(*this);
}

}  // namespace penumbra
