// DeformPass: playback's pose on the GPU. For each played primitive (GpuScene::deformed) it
// runs glsl/deform.vert over the rest data (morph targets by their weights, then the skin's
// joints) and captures the posed positions, normals and tangents into the primitive's own vertex
// buffers by transform feedback: once per pose, where skinning in every pass's vertex shader
// would redo it for the prepass, each shadow map and the lighting of every frame.
#pragma once

#include <array>
#include <cstdint>
#include <map>

#include "gl/objects.h"
#include "gl/program.h"
#include "gpu/gpu_scene.h"
#include "penumbra/animation.h"

namespace penumbra::passes {

// X(field, DEFINE, bits): deform.vert's switches. DeformKey makes the key and every #define
// from this one table (as ProgramKey does for the lighting programs).
#define PN_DEFORM_SWITCHES(X)                         \
  X(skin, PN_SKIN, 1)         /* joints and weights */ \
  X(morph, PN_MORPH, 1)       /* morph targets */      \
  X(tangents, PN_TANGENTS, 1) /* a tangent to pose */

struct DeformKey {
#define PN_DEFORM_FIELD(field, define, bits) uint32_t field = 0;
  PN_DEFORM_SWITCHES(PN_DEFORM_FIELD)
#undef PN_DEFORM_FIELD
  uint32_t key() const;
  gl::Defines defines() const;
};

class DeformPass {
 public:
  static Result<DeformPass> create(gl::ShaderLibrary& library);
  // Writes every played primitive of `scene` at `pose` (after GpuScene::pose took its joints).
  Status run(const GpuScene& scene, const Pose& pose);

 private:
  Result<gl::Program*> program(const DeformKey& key);
  gl::ShaderLibrary* library_ = nullptr;
  gl::TransformFeedback feedback_;
  gl::Texture2D empty_;  // on the samplers a variant reads but a primitive lacks
  // A draw needs a complete framebuffer even with nothing rasterized (a surfaceless context
  // has no default one): a 1x1 target no one reads.
  gl::Texture2D pixel_;
  gl::Framebuffer framebuffer_;
  std::map<uint32_t, gl::Program*> programs_;
};

}  // namespace penumbra::passes
