// LightingPass::drawGround: the shadow-catching ground (RenderSettings::shadowIntensity,
// model-viewer's shadow-intensity; glsl/ground.frag says how it shades). A square on the plane
// under the scene's bounds, centred under them, reaching 1.5 times their largest side from the
// centre (scene units from the scene itself), its darkening faded out over its outer half. Drawn after the first batch's opaque surfaces and its
// background, depth-tested against the surfaces, it multiplies the frame behind it; it is not
// in the scene's lists, so it casts no shadow, holds no depth, and neither the occlusion rays,
// the probes nor the caches see it: the scene is lit as without it.
#include <algorithm>

#include "passes/lighting_pass.h"

namespace penumbra::passes {

Status LightingPass::drawGround(const LightingBatch& b, const glm::mat3& envRotation) {
  const Bounds& box = b.scene->bounds();
  if (!box.valid()) return {};
  LightingVariant v = variant(b, false, false, !b.punctual.empty());
  // The probes (when on and filled) give the light the scene reflects onto the ground.
  v.probeCache = v.lightCache = v.accumulate = 0;
  const ProgramKey key(v, MaterialFeatures{});
  gl::Program*& p = groundPrograms_[key.key()];
  if (!p) {
    auto made = library_->program("ground.vert", "ground.frag", key.defines());
    if (!made) return made.error();
    p = *made;
  }
  if (groundVao_.id() == 0) groundVao_ = gl::VertexArray::create();
  setUniforms(*p, b, envRotation);
  const glm::vec3 size = box.max - box.min;
  p->set("uGroundCenter", glm::vec3(0.5f * (box.min.x + box.max.x), box.min.y,
                                    0.5f * (box.min.z + box.max.z)));
  p->set("uGroundHalf", 1.5f * std::max({size.x, size.y, size.z}));
  p->set("uShadowIntensity", b.settings->shadowIntensity);  // (0..1: the settings schema)
  p->set("uTransparent", b.settings->transparentBackground ? 1.0f : 0.0f);
  gl::apply({.depthTest = gl::DepthTest::Less,
             .depthWrite = false,
             .blend = gl::Blend::Multiply,
             .cull = gl::Cull::Back});
  groundVao_.draw(gl::Primitive::TriangleStrip, 4);
  gl::apply({});
  return {};
}

}  // namespace penumbra::passes
