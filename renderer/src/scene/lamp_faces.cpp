// Lamp meshes found without markup: a modeller who places an EXT_lights_area light in a light
// fitting usually also gives the fitting an emissive surface, and both would then light the
// room (the analytic light, and the emissive surface through the probe volume and screen-space
// indirect light). An emissive surface that sits on an area light is taken as that light's
// visible face, as extras.area_light_proxy says explicitly: it blocks no light and lights
// nothing itself, and the camera still sees it.
#include <algorithm>

#include "scene/gltf_document.h"

namespace penumbra::gltf {
namespace {

float diagonal(const Bounds& b) {
  return b.valid() ? glm::length(b.max - b.min) : 0.0f;
}

}  // namespace

void markLampFaces(Scene& scene, LoadContext& ctx) {
  for (Instance& inst : scene.instances) {
    if (!inst.castsShadow || inst.mesh < 0) continue;  // already an explicit proxy
    Bounds glow;                                       // the instance's emissive primitives
    for (const Primitive& p : scene.meshes[static_cast<size_t>(inst.mesh)].primitives) {
      if (p.material >= 0 && p.material < static_cast<int>(scene.materials.size()) &&
          scene.materials[static_cast<size_t>(p.material)].emits()) {
        glow.extend(p.bounds.transformed(inst.world));
      }
    }
    if (!glow.valid()) continue;
    for (const Light& l : scene.lights) {
      if (!l.isArea()) continue;
      // Sizes relative to the light's own: no scene-unit constant. The glowing part is at most
      // four times the light across (a fitting, not a wall), and the light's centre lies on it
      // or within half of the larger of the two sizes.
      const float lightSize = glm::length(glm::vec2(l.width, l.height));
      const float glowSize = diagonal(glow);
      if (glowSize > 4.0f * lightSize) continue;
      const float margin = 0.5f * std::max(lightSize, glowSize);
      const glm::vec3 nearest = glm::clamp(l.position, glow.min, glow.max);
      if (glm::length(l.position - nearest) > margin) continue;
      inst.lampFace = true;
      ctx.warn("node '" + inst.nodeName + "': its emissive surface sits on area light '" + l.name +
               "' and is taken as that light's visible face (it lights nothing itself; "
               "extras.area_light_proxy says so explicitly)");
      break;
    }
  }
}

}  // namespace penumbra::gltf
