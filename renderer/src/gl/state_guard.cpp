#include "gl/state_guard.h"

#include <cstddef>

#include "gl/gl.h"

namespace penumbra::gl {
namespace {

constexpr GLenum kEnables[] = {GL_BLEND,        GL_DEPTH_TEST,         GL_CULL_FACE,
                               GL_SCISSOR_TEST, GL_STENCIL_TEST,       GL_POLYGON_OFFSET_FILL,
                               GL_DITHER,       GL_RASTERIZER_DISCARD, GL_SAMPLE_ALPHA_TO_COVERAGE};
constexpr GLenum kPixelStore[] = {GL_PACK_ALIGNMENT,    GL_UNPACK_ALIGNMENT,  GL_PACK_ROW_LENGTH,
                                  GL_UNPACK_ROW_LENGTH, GL_PACK_SKIP_ROWS,    GL_PACK_SKIP_PIXELS,
                                  GL_UNPACK_SKIP_ROWS,  GL_UNPACK_SKIP_PIXELS};
// What Penumbra's own code assumes while it runs.
constexpr int kPixelStoreDefaults[] = {1, 1, 0, 0, 0, 0, 0, 0};
constexpr bool kEnableDefaults[] = {false, false, false, false, false, false, true, false, false};

int get(GLenum name) {
  GLint v = 0;
  glGetIntegerv(name, &v);
  return v;
}

void setEnabled(GLenum cap, bool on) {
  if (on) {
    glEnable(cap);
  } else {
    glDisable(cap);
  }
}

}  // namespace

StateGuard::StateGuard(bool active) : active_(active) {
  if (!active_) return;
  drawFramebuffer_ = get(GL_DRAW_FRAMEBUFFER_BINDING);
  readFramebuffer_ = get(GL_READ_FRAMEBUFFER_BINDING);
  renderbuffer_ = get(GL_RENDERBUFFER_BINDING);
  glGetIntegerv(GL_VIEWPORT, viewport_.data());
  glGetIntegerv(GL_SCISSOR_BOX, scissor_.data());  // a frame drawn in bands sets its own
  program_ = get(GL_CURRENT_PROGRAM);
  vertexArray_ = get(GL_VERTEX_ARRAY_BINDING);
  arrayBuffer_ = get(GL_ARRAY_BUFFER_BINDING);
  elementBuffer_ = get(GL_ELEMENT_ARRAY_BUFFER_BINDING);
  uniformBuffer_ = get(GL_UNIFORM_BUFFER_BINDING);
  packBuffer_ = get(GL_PIXEL_PACK_BUFFER_BINDING);
  unpackBuffer_ = get(GL_PIXEL_UNPACK_BUFFER_BINDING);
  activeTexture_ = get(GL_ACTIVE_TEXTURE);
  for (int i = 0; i < kUnits; ++i) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + i));
    texture2d_[static_cast<std::size_t>(i)] = get(GL_TEXTURE_BINDING_2D);
    textureCube_[static_cast<std::size_t>(i)] = get(GL_TEXTURE_BINDING_CUBE_MAP);
    sampler_[static_cast<std::size_t>(i)] = get(GL_SAMPLER_BINDING);
    glBindSampler(static_cast<GLuint>(i), 0);
  }
  glActiveTexture(GL_TEXTURE0);
  for (std::size_t i = 0; i < enabled_.size(); ++i) {
    enabled_[i] = glIsEnabled(kEnables[i]) == GL_TRUE;
    setEnabled(kEnables[i], kEnableDefaults[i]);
  }
  const GLenum blend[] = {GL_BLEND_SRC_RGB,   GL_BLEND_DST_RGB,      GL_BLEND_SRC_ALPHA,
                          GL_BLEND_DST_ALPHA, GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA};
  for (std::size_t i = 0; i < blend_.size(); ++i) blend_[i] = get(blend[i]);
  glGetFloatv(GL_BLEND_COLOR, blendColor_.data());
  glGetFloatv(GL_COLOR_CLEAR_VALUE, clearColor_.data());
  glGetFloatv(GL_DEPTH_CLEAR_VALUE, &clearDepth_);
  depthFunc_ = get(GL_DEPTH_FUNC);
  cullFace_ = get(GL_CULL_FACE_MODE);
  frontFace_ = get(GL_FRONT_FACE);
  GLboolean b = GL_TRUE;
  glGetBooleanv(GL_DEPTH_WRITEMASK, &b);
  depthMask_ = b == GL_TRUE;
  GLboolean mask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
  glGetBooleanv(GL_COLOR_WRITEMASK, mask);
  for (int i = 0; i < 4; ++i) colorMask_[static_cast<std::size_t>(i)] = mask[i] == GL_TRUE;
  // Front and back stencil state: setStencil() sets both.
  const GLenum stencil[] = {GL_STENCIL_FUNC,
                            GL_STENCIL_REF,
                            GL_STENCIL_VALUE_MASK,
                            GL_STENCIL_FAIL,
                            GL_STENCIL_PASS_DEPTH_FAIL,
                            GL_STENCIL_PASS_DEPTH_PASS,
                            GL_STENCIL_WRITEMASK,
                            GL_STENCIL_BACK_FUNC,
                            GL_STENCIL_BACK_REF,
                            GL_STENCIL_BACK_VALUE_MASK,
                            GL_STENCIL_BACK_FAIL,
                            GL_STENCIL_BACK_PASS_DEPTH_FAIL,
                            GL_STENCIL_BACK_PASS_DEPTH_PASS,
                            GL_STENCIL_BACK_WRITEMASK,
                            GL_STENCIL_CLEAR_VALUE};
  for (std::size_t i = 0; i < stencil_.size(); ++i) stencil_[i] = get(stencil[i]);
  glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &polygonOffset_[0]);
  glGetFloatv(GL_POLYGON_OFFSET_UNITS, &polygonOffset_[1]);
  for (std::size_t i = 0; i < pixelStore_.size(); ++i) {
    pixelStore_[i] = get(kPixelStore[i]);
    glPixelStorei(kPixelStore[i], kPixelStoreDefaults[i]);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

StateGuard::~StateGuard() {
  if (!active_) return;
  for (std::size_t i = 0; i < pixelStore_.size(); ++i)
    glPixelStorei(kPixelStore[i], pixelStore_[i]);
  glPolygonOffset(polygonOffset_[0], polygonOffset_[1]);
  const auto st = [&](std::size_t i) { return static_cast<GLuint>(stencil_[i]); };
  for (std::size_t face = 0; face < 2; ++face) {
    const GLenum f = face == 0 ? GL_FRONT : GL_BACK;
    const std::size_t o = face * 7;
    glStencilFuncSeparate(f, st(o), stencil_[o + 1], st(o + 2));
    glStencilOpSeparate(f, st(o + 3), st(o + 4), st(o + 5));
    glStencilMaskSeparate(f, st(o + 6));
  }
  glClearStencil(stencil_[14]);
  glColorMask(colorMask_[0], colorMask_[1], colorMask_[2], colorMask_[3]);
  glDepthMask(depthMask_ ? GL_TRUE : GL_FALSE);
  glFrontFace(static_cast<GLenum>(frontFace_));
  glCullFace(static_cast<GLenum>(cullFace_));
  glDepthFunc(static_cast<GLenum>(depthFunc_));
  glClearDepthf(clearDepth_);
  glClearColor(clearColor_[0], clearColor_[1], clearColor_[2], clearColor_[3]);
  glBlendColor(blendColor_[0], blendColor_[1], blendColor_[2], blendColor_[3]);
  glBlendEquationSeparate(static_cast<GLenum>(blend_[4]), static_cast<GLenum>(blend_[5]));
  glBlendFuncSeparate(static_cast<GLenum>(blend_[0]), static_cast<GLenum>(blend_[1]),
                      static_cast<GLenum>(blend_[2]), static_cast<GLenum>(blend_[3]));
  for (std::size_t i = 0; i < enabled_.size(); ++i) setEnabled(kEnables[i], enabled_[i]);
  for (int i = 0; i < kUnits; ++i) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + i));
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(texture2d_[static_cast<std::size_t>(i)]));
    glBindTexture(GL_TEXTURE_CUBE_MAP,
                  static_cast<GLuint>(textureCube_[static_cast<std::size_t>(i)]));
    glBindSampler(static_cast<GLuint>(i),
                  static_cast<GLuint>(sampler_[static_cast<std::size_t>(i)]));
  }
  glActiveTexture(static_cast<GLenum>(activeTexture_));
  glBindVertexArray(static_cast<GLuint>(vertexArray_));
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLuint>(elementBuffer_));
  glBindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(arrayBuffer_));
  glBindBuffer(GL_UNIFORM_BUFFER, static_cast<GLuint>(uniformBuffer_));
  glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(packBuffer_));
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(unpackBuffer_));
  glUseProgram(static_cast<GLuint>(program_));
  glBindRenderbuffer(GL_RENDERBUFFER, static_cast<GLuint>(renderbuffer_));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(drawFramebuffer_));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(readFramebuffer_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glScissor(scissor_[0], scissor_[1], scissor_[2], scissor_[3]);
}

}  // namespace penumbra::gl
