// Cameras and lights placed by nodes: EXT_lights_area (draft vendor extension, KhronosGroup/glTF
// PR 2525) rect and disk lights, and KHR_lights_punctual point, spot and directional lights.
// Both emit along the node's local -Z, like glTF cameras look.
#include <algorithm>
#include <cmath>

#include "scene/gltf_document.h"
#include "scene/light_kinds.h"

namespace penumbra::gltf {
namespace {

bool finiteVec(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Unit vector along `v`, or nullopt-like zero when it has no direction.
glm::vec3 unit(const glm::vec3& v) {
  const float len = glm::length(v);
  return len > 0.0f && std::isfinite(len) ? v / len : glm::vec3(0.0f);
}

std::string lightLabel(const char* ext, int index, const std::string& name) {
  return std::string(ext) + " light " + std::to_string(index) +
         (name.empty() ? "" : " ('" + name + "')");
}

}  // namespace

void addNodeCamera(const Document& doc, const NodeDesc& node, const glm::mat4& world, Scene& scene,
                   LoadContext& ctx) {
  const CameraDesc& desc = doc.cameras[static_cast<size_t>(node.camera)];
  Camera cam;
  cam.name = !desc.name.empty() ? desc.name : node.name;
  if (cam.name.empty()) cam.name = "camera " + std::to_string(node.camera);
  // Remove scale (and shear) but keep where the camera looks (-Z) and its up (+Y); X is
  // rebuilt so the frame is a proper right-handed rotation even under a mirroring parent.
  const glm::vec3 z = unit(glm::vec3(world[2]));
  const glm::vec3 y = unit(glm::vec3(world[1]) - z * glm::dot(z, glm::vec3(world[1])));
  if (glm::length(z) == 0.0f || glm::length(y) == 0.0f) {
    ctx.warn("camera '" + cam.name + "' has a degenerate (zero-scale) transform; skipped");
    return;
  }
  const glm::vec3 x = glm::cross(y, z);
  cam.world = glm::mat4(glm::vec4(x, 0), glm::vec4(y, 0), glm::vec4(z, 0), world[3]);
  cam.yfov = desc.yfov;
  cam.aspect = desc.perspective ? desc.aspect : std::abs(desc.xmag / desc.ymag);
  cam.znear = desc.znear;
  cam.zfar = desc.zfar;
  cam.orthographic = !desc.perspective;
  cam.ymag = desc.ymag;
  scene.cameras.push_back(cam);
}

void addNodeLights(const Document& doc, const NodeDesc& node, const glm::mat4& world, Scene& scene,
                   LoadContext& ctx) {
  const glm::vec3 axisX(world[0]), axisY(world[1]), axisZ(world[2]);
  auto place = [&](Light& l) {
    l.position = glm::vec3(world[3]);
    l.right = unit(axisX);
    l.up = unit(axisY);
    l.direction = -unit(axisZ);
  };

  if (node.areaLight >= 0) {
    const LightDesc& d = doc.areaLights[static_cast<size_t>(node.areaLight)];
    const std::string label = lightLabel("EXT_lights_area", node.areaLight, d.name);
    Light l;
    l.name = !d.name.empty() ? d.name : node.name;
    l.type = d.type;
    l.color = d.color;
    l.intensity = d.intensity;
    place(l);
    // The light's size scales with the largest axis of the node's world scale.
    const float scale = std::max({glm::length(axisX), glm::length(axisY), glm::length(axisZ)});
    // A rect's size is its height and aspect its width / height; a disk's size its diameter.
    l.width = scale * d.size *
              (lightKind(d.type).samples == progressive::LightShape::Rect ? d.aspect : 1.0f);
    l.height = scale * d.size;
    const bool frame = glm::length(l.direction) > 0.0f && glm::length(l.right) > 0.0f &&
                       glm::length(l.up) > 0.0f && finiteVec(l.position);
    if (!(l.intensity >= 0.0f) || !std::isfinite(l.intensity)) {
      ctx.warn(label + " has a negative or invalid intensity; dropped");
    } else if (!(l.width > 0.0f) || !(l.height > 0.0f) || !std::isfinite(l.area()) || !frame) {
      ctx.warn(label + " on node '" + node.name +
               "' has zero area or a degenerate transform; dropped");
    } else {
      scene.lights.push_back(l);
    }
  }

  if (node.punctualLight >= 0) {
    const LightDesc& d = doc.punctualLights[static_cast<size_t>(node.punctualLight)];
    const std::string label = lightLabel("KHR_lights_punctual", node.punctualLight, d.name);
    Light l;
    l.name = !d.name.empty() ? d.name : node.name;
    l.type = d.type;
    l.color = d.color;
    l.intensity = d.intensity;
    l.range = std::max(d.range, 0.0f);
    place(l);
    // The specification asks for 0 <= inner < outer <= pi/2; clamp rather than reject.
    l.outerConeAngle = std::clamp(d.outerConeAngle, 0.0f, 1.57079633f);
    l.innerConeAngle = std::clamp(d.innerConeAngle, 0.0f, l.outerConeAngle);
    if (!(l.intensity >= 0.0f) || !std::isfinite(l.intensity)) {
      ctx.warn(label + " has a negative or invalid intensity; dropped");
    } else if (l.type != LightType::Point && glm::length(l.direction) == 0.0f) {
      ctx.warn(label + " on node '" + node.name + "' has a degenerate transform; dropped");
    } else {
      scene.lights.push_back(l);
    }
  }
}

}  // namespace penumbra::gltf
