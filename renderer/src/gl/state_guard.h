// StateGuard: saves the part of the GL state Penumbra's passes change and restores it when it
// goes out of scope, so a Renderer running in a host's context (GlContext::adoptCurrent,
// RendererOptions::preserveHostState) leaves the host's state as it found it. For its lifetime
// it also puts in place what Penumbra relies on: no sampler objects or pixel buffers bound,
// tight pixel packing, no scissor, stencil, dithering-free output or rasterizer discard.
// What it covers is listed in docs/embedding.md.
#pragma once

#include <array>

namespace penumbra::gl {

class StateGuard {
 public:
  static constexpr int kUnits = 16;  // texture units saved (Penumbra uses 0..15)
  // Does nothing when `active` is false (a Renderer in a context of its own).
  explicit StateGuard(bool active);
  ~StateGuard();
  StateGuard(const StateGuard&) = delete;
  StateGuard& operator=(const StateGuard&) = delete;

 private:
  bool active_;
  int drawFramebuffer_ = 0, readFramebuffer_ = 0, renderbuffer_ = 0;
  std::array<int, 4> viewport_{}, scissor_{};
  int program_ = 0, vertexArray_ = 0, arrayBuffer_ = 0, elementBuffer_ = 0, uniformBuffer_ = 0;
  int packBuffer_ = 0, unpackBuffer_ = 0;
  int activeTexture_ = 0;
  std::array<int, kUnits> texture2d_{}, textureCube_{}, sampler_{};
  std::array<bool, 9> enabled_{};
  std::array<int, 6> blend_{};  // src rgb, dst rgb, src alpha, dst alpha, eq rgb, eq alpha
  std::array<float, 4> blendColor_{}, clearColor_{};
  int depthFunc_ = 0, cullFace_ = 0, frontFace_ = 0;
  std::array<int, 15> stencil_{};  // front and back func/ref/mask/ops/writemask, clear value
  bool depthMask_ = true;
  std::array<bool, 4> colorMask_{};
  float polygonOffset_[2] = {0, 0}, clearDepth_ = 1;
  std::array<int, 8> pixelStore_{};
};

}  // namespace penumbra::gl
