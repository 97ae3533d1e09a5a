#include "passes/deform_pass.h"

#include <algorithm>
#include <string>
#include <vector>

#include "gl/errors.h"

namespace penumbra::passes {

uint32_t DeformKey::key() const {
  uint32_t k = 0;
  int shift = 0;
#define PN_DEFORM_PACK(field, define, bits)                                          \
  PN_CHECK(field < (1u << (bits)), "DeformKey: " #field " does not fit its bits"); \
  k |= field << shift;                                                               \
  shift += (bits);
  PN_DEFORM_SWITCHES(PN_DEFORM_PACK)
#undef PN_DEFORM_PACK
  return k;
}

gl::Defines DeformKey::defines() const {
  gl::Defines d;
#define PN_DEFORM_DEFINE(field, define, bits) d.emplace_back(#define, std::to_string(field));
  PN_DEFORM_SWITCHES(PN_DEFORM_DEFINE)
#undef PN_DEFORM_DEFINE
  d.emplace_back("PN_MAX_MORPH_TARGETS", std::to_string(kMaxMorphTargets));
  return d;
}

Result<DeformPass> DeformPass::create(gl::ShaderLibrary& library) {
  DeformPass pass;
  pass.library_ = &library;
  pass.feedback_ = gl::TransformFeedback::create();
  gl::TextureDesc desc{.width = 1, .height = 1, .format = gl::PixelFormat::RGBA32F};
  desc.sampler.minFilter = desc.sampler.magFilter = gl::Filter::Nearest;
  auto empty = gl::Texture2D::create(desc);
  if (!empty) return empty.error();
  const float zero[4] = {0, 0, 0, 0};
  empty->upload(0, zero, gl::DataType::Float);
  pass.empty_ = std::move(*empty);
  auto pixel = gl::Texture2D::create({.width = 1, .height = 1, .format = gl::PixelFormat::RGBA8});
  if (!pixel) return pixel.error();
  pass.pixel_ = std::move(*pixel);
  pass.framebuffer_ = gl::Framebuffer::create();
  pass.framebuffer_.attachColor(0, pass.pixel_);
  PN_TRY(pass.framebuffer_.checkComplete());
  return pass;
}

Result<gl::Program*> DeformPass::program(const DeformKey& key) {
  if (auto it = programs_.find(key.key()); it != programs_.end()) return it->second;
  std::vector<std::string> outputs = {"vPosition", "vNormal"};
  if (key.tangents) outputs.push_back("vTangent");
  auto p = library_->program("deform.vert", "deform.frag", key.defines(), outputs);
  if (!p) return p.error();
  programs_.emplace(key.key(), *p);
  return *p;
}

Status DeformPass::run(const GpuScene& scene, const Pose& pose) {
  framebuffer_.bind();
  for (const GpuPrimitive* prim : scene.deformed()) {
    const GpuDeformation& d = *prim->deformation;
    if (prim->posedBuffer[0] < 0 || prim->posedBuffer[1] < 0) continue;  // nothing to write
    const int skin = scene.skinOf(d.mesh);
    const bool skinned = d.skinned && pose.jointsOf(skin);
    const std::vector<float>& weights = pose.weightsOf(d.mesh);
    const int targets = std::min(d.targets, static_cast<int>(weights.size()));
    const bool tangents = d.tangents && prim->posedBuffer[2] >= 0;
    DeformKey key;
    key.skin = skinned ? 1u : 0u;
    key.morph = targets > 0 ? 1u : 0u;
    key.tangents = tangents ? 1u : 0u;
    auto p = program(key);
    if (!p) return p.error();
    const gl::Program& prog = **p;
    prog.use();
    if (key.morph) {
      std::vector<glm::vec4> packed(kMaxMorphTargets / 4, glm::vec4(0.0f));
      for (int t = 0; t < targets; ++t) packed[static_cast<size_t>(t / 4)][t % 4] = weights[static_cast<size_t>(t)];
      prog.set("uMorphWeights", std::span<const glm::vec4>(packed));
      prog.set("uMorphTargets", targets);
      prog.set("uVertexCount", d.vertexCount);
      prog.set("uMorphWidth", std::max(d.morphWidth, 1));
      prog.bind("uMorphs", d.morphs ? d.morphs : empty_);
    }
    if (key.skin) {
      const gl::Texture2D& joints = scene.jointTexture(skin);
      prog.set("uJointCount", std::max(joints.height(), 1));
      prog.bind("uJoints", joints ? joints : empty_);
    }
    const gl::Buffer* outputs[3] = {&prim->buffers[static_cast<size_t>(prim->posedBuffer[0])],
                                    &prim->buffers[static_cast<size_t>(prim->posedBuffer[1])],
                                    tangents ? &prim->buffers[static_cast<size_t>(prim->posedBuffer[2])]
                                             : nullptr};
    feedback_.capture(d.rest, d.vertexCount,
                      std::span<const gl::Buffer* const>(outputs, tangents ? 3 : 2));
  }
  return gl::checkError("posing the played primitives");
}

}  // namespace penumbra::passes
