#include "gl/objects.h"

#include <string>

#include "gl/errors.h"

namespace penumbra::gl {
namespace {

GLenum bufferTarget(BufferKind k) {
  switch (k) {
    case BufferKind::Vertex:
      return GL_ARRAY_BUFFER;
    case BufferKind::Index:
      return GL_ELEMENT_ARRAY_BUFFER;
    case BufferKind::Uniform:
      return GL_UNIFORM_BUFFER;
    case BufferKind::Feedback:
      return GL_ARRAY_BUFFER;
  }
  return GL_ARRAY_BUFFER;
}

GLenum glType(AttribType t) {
  switch (t) {
    case AttribType::Float:
      return GL_FLOAT;
    case AttribType::UInt8:
      return GL_UNSIGNED_BYTE;
    case AttribType::UInt16:
      return GL_UNSIGNED_SHORT;
    case AttribType::Int8:
      return GL_BYTE;
    case AttribType::Int16:
      return GL_SHORT;
  }
  return GL_FLOAT;
}

GLenum glIndexType(IndexType t) {
  switch (t) {
    case IndexType::UInt8:
      return GL_UNSIGNED_BYTE;
    case IndexType::UInt16:
      return GL_UNSIGNED_SHORT;
    case IndexType::UInt32:
      return GL_UNSIGNED_INT;
  }
  return GL_UNSIGNED_INT;
}

GLenum glPrimitive(Primitive p) {
  switch (p) {
    case Primitive::Triangles:
      return GL_TRIANGLES;
    case Primitive::TriangleStrip:
      return GL_TRIANGLE_STRIP;
    case Primitive::Lines:
      return GL_LINES;
    case Primitive::Points:
      return GL_POINTS;
  }
  return GL_TRIANGLES;
}

}  // namespace

// --- Buffer -------------------------------------------------------------------------------

Result<Buffer> Buffer::create(BufferKind kind, std::span<const uint8_t> data) {
  beginAllocation();
  GLuint id = 0;
  glGenBuffers(1, &id);
  Buffer b;
  b.handle_ = Handle<deleteBuffer>(id);
  b.kind_ = kind;
  b.size_ = data.size();
  // Index buffers are bound through a VAO; binding one with no VAO bound is harmless in ES3.
  glBindBuffer(bufferTarget(kind), id);
  glBufferData(bufferTarget(kind), static_cast<GLsizeiptr>(data.size()),
               data.empty() ? nullptr : data.data(),
               kind == BufferKind::Feedback ? GL_DYNAMIC_COPY : GL_STATIC_DRAW);
  if (kind == BufferKind::Index) glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  PN_TRY(checkAllocation("allocating a " + std::to_string(data.size()) + "-byte buffer"));
  b.memory_ = MemoryCharge(static_cast<int64_t>(data.size()));
  return b;
}

void Buffer::update(size_t offset, std::span<const uint8_t> data) {
  PN_CHECK(offset + data.size() <= size_, "buffer update out of range");
  glBindBuffer(bufferTarget(kind_), handle_.id());
  glBufferSubData(bufferTarget(kind_), static_cast<GLintptr>(offset),
                  static_cast<GLsizeiptr>(data.size()), data.data());
}

void Buffer::bind() const {
  glBindBuffer(bufferTarget(kind_), handle_.id());
}

// --- VertexArray --------------------------------------------------------------------------

VertexArray VertexArray::create() {
  GLuint id = 0;
  glGenVertexArrays(1, &id);
  VertexArray v;
  v.handle_ = Handle<deleteVertexArray>(id);
  return v;
}

void VertexArray::setAttribute(int location, const Buffer& buffer, int components, AttribType type,
                               bool normalized, int stride, size_t offset) {
  glBindVertexArray(handle_.id());
  glBindBuffer(GL_ARRAY_BUFFER, buffer.id());
  glEnableVertexAttribArray(static_cast<GLuint>(location));
  glVertexAttribPointer(static_cast<GLuint>(location), components, glType(type),
                        normalized ? GL_TRUE : GL_FALSE, stride,
                        reinterpret_cast<const void*>(offset));
  glBindVertexArray(0);
}

void VertexArray::setConstant(int location, float x, float y, float z, float w) {
  // Constant attribute values are context state, not VAO state: re-applied at bind().
  constants_.push_back({location, {x, y, z, w}});
}

void VertexArray::setInstanceRows(int location, const Buffer* buffer, size_t offset,
                                  int divisor) const {
  glBindVertexArray(handle_.id());
  constexpr GLsizei kStride = 12 * sizeof(float);
  for (int row = 0; row < 3; ++row) {
    const auto loc = static_cast<GLuint>(location + row);
    if (buffer != nullptr) {
      glBindBuffer(GL_ARRAY_BUFFER, buffer->id());
      glEnableVertexAttribArray(loc);
      glVertexAttribPointer(loc, 4, GL_FLOAT, GL_FALSE, kStride,
                            reinterpret_cast<const void*>(offset + row * 4 * sizeof(float)));
      glVertexAttribDivisor(loc, static_cast<GLuint>(divisor));
    } else {
      glDisableVertexAttribArray(loc);
      glVertexAttrib4f(loc, row == 0 ? 1.0f : 0.0f, row == 1 ? 1.0f : 0.0f,
                       row == 2 ? 1.0f : 0.0f, 0.0f);
    }
  }
}

void VertexArray::setIndexBuffer(const Buffer& buffer, IndexType type) {
  glBindVertexArray(handle_.id());
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffer.id());
  glBindVertexArray(0);
  indexed_ = true;
  indexType_ = type;
}

void VertexArray::bind() const {
  glBindVertexArray(handle_.id());
  for (const auto& [loc, v] : constants_) {
    glVertexAttrib4f(static_cast<GLuint>(loc), v[0], v[1], v[2], v[3]);
  }
}

void VertexArray::draw(Primitive mode, int count, size_t firstOrByteOffset) const {
  bind();
  if (indexed_) {
    glDrawElements(glPrimitive(mode), count, glIndexType(indexType_),
                   reinterpret_cast<const void*>(firstOrByteOffset));
  } else {
    glDrawArrays(glPrimitive(mode), static_cast<GLint>(firstOrByteOffset), count);
  }
}

void VertexArray::drawInstanced(Primitive mode, int count, int instances,
                                size_t firstOrByteOffset) const {
  bind();
  if (indexed_) {
    glDrawElementsInstanced(glPrimitive(mode), count, glIndexType(indexType_),
                            reinterpret_cast<const void*>(firstOrByteOffset), instances);
  } else {
    glDrawArraysInstanced(glPrimitive(mode), static_cast<GLint>(firstOrByteOffset), count,
                          instances);
  }
}

// --- Renderbuffer -------------------------------------------------------------------------

Result<Renderbuffer> Renderbuffer::create(int width, int height, PixelFormat format) {
  beginAllocation();
  GLuint id = 0;
  glGenRenderbuffers(1, &id);
  Renderbuffer r;
  r.handle_ = Handle<deleteRenderbuffer>(id);
  r.format_ = format;
  GLenum internal = GL_DEPTH_COMPONENT24;
  switch (format) {
    case PixelFormat::Depth24:
      internal = GL_DEPTH_COMPONENT24;
      break;
    case PixelFormat::Depth32F:
      internal = GL_DEPTH_COMPONENT32F;
      break;
    case PixelFormat::Depth24Stencil8:
      internal = GL_DEPTH24_STENCIL8;
      break;
    case PixelFormat::RGBA8:
      internal = GL_RGBA8;
      break;
    case PixelFormat::RGBA16F:
      internal = GL_RGBA16F;
      break;
    case PixelFormat::RGBA32F:
      internal = GL_RGBA32F;
      break;
    default:
      return makeError(std::string("renderbuffers of format ") + formatName(format) +
                       " are not supported");
  }
  glBindRenderbuffer(GL_RENDERBUFFER, id);
  glRenderbufferStorage(GL_RENDERBUFFER, internal, width, height);
  PN_TRY(checkAllocation("allocating a " + std::to_string(width) + "x" + std::to_string(height) +
                    " renderbuffer"));
  r.memory_ = MemoryCharge(storageBytes(width, height, 1, bytesPerPixel(format)));
  return r;
}

// --- Framebuffer --------------------------------------------------------------------------

Framebuffer Framebuffer::create() {
  GLuint id = 0;
  glGenFramebuffers(1, &id);
  Framebuffer f;
  f.handle_ = Handle<deleteFramebuffer>(id);
  return f;
}

void Framebuffer::attachColor(int index, const Texture2D& texture, int level) {
  bind();
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + index, GL_TEXTURE_2D, texture.id(),
                         level);
}

void Framebuffer::attachColor(int index, const TextureCube& cube, int face, int level) {
  bind();
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + index,
                         GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, cube.id(), level);
}

void Framebuffer::attachDepth(const Texture2D& texture) {
  bind();
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, texture.id(), 0);
}

void Framebuffer::attachColor(int index, const Texture2DArray& array, int layer) {
  PN_CHECK(layer >= 0 && layer < array.layers(), "texture array layer out of range");
  bind();
  glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(index),
                            array.id(), 0, layer);
}

void Framebuffer::attachDepth(const Texture2DArray& array, int layer) {
  PN_CHECK(layer >= 0 && layer < array.layers(), "texture array layer out of range");
  bind();
  glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, array.id(), 0, layer);
}

void Framebuffer::attachDepth(const TextureCube& cube, int face) {
  bind();
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_CUBE_MAP_POSITIVE_X + face,
                         cube.id(), 0);
}

void Framebuffer::attachDepth(const Renderbuffer& renderbuffer) {
  bind();
  const GLenum attachment = renderbuffer.format() == PixelFormat::Depth24Stencil8
                                ? GL_DEPTH_STENCIL_ATTACHMENT
                                : GL_DEPTH_ATTACHMENT;
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, attachment, GL_RENDERBUFFER, renderbuffer.id());
}

void Framebuffer::setDrawBuffers(int count) {
  bind();
  GLenum bufs[8];
  for (int i = 0; i < count && i < 8; ++i) bufs[i] = GL_COLOR_ATTACHMENT0 + i;
  if (count == 0) {
    GLenum none = GL_NONE;
    glDrawBuffers(1, &none);
    glReadBuffer(GL_NONE);
  } else {
    glDrawBuffers(count, bufs);
  }
}

Status Framebuffer::checkComplete() const {
  bind();
  GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_COMPLETE) return {};
  return makeError(std::string("framebuffer incomplete: ") + framebufferStatusName(status));
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, handle_.id());
}
void Framebuffer::bindDefault() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}
void Framebuffer::bindExternal(GLuint id) {
  glBindFramebuffer(GL_FRAMEBUFFER, id);
}

void Framebuffer::blitColorTo(const Framebuffer& target, int width, int height) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, handle_.id());
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target.id());
  glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, target.id());
}

std::vector<float> Framebuffer::readRgbaFloat(int index, int x, int y, int width,
                                              int height) const {
  std::vector<float> out(static_cast<size_t>(width) * height * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, handle_.id());
  glReadBuffer(GL_COLOR_ATTACHMENT0 + index);
  glReadPixels(x, y, width, height, GL_RGBA, GL_FLOAT, out.data());
  return out;
}

std::vector<uint8_t> Framebuffer::readRgba8(int index, int x, int y, int width, int height) const {
  std::vector<uint8_t> out(static_cast<size_t>(width) * height * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, handle_.id());
  glReadBuffer(GL_COLOR_ATTACHMENT0 + index);
  glReadPixels(x, y, width, height, GL_RGBA, GL_UNSIGNED_BYTE, out.data());
  return out;
}

// --- TimerQuery ---------------------------------------------------------------------------

std::optional<TimerQuery> TimerQuery::create(bool supported) {
  if (!supported) return std::nullopt;
  GLuint id = 0;
  glGenQueries(1, &id);
  TimerQuery q;
  q.handle_ = Handle<deleteQuery>(id);
  return q;
}

void TimerQuery::begin() {
  glBeginQuery(GL_TIME_ELAPSED_EXT, handle_.id());
}
void TimerQuery::end() {
  glEndQuery(GL_TIME_ELAPSED_EXT);
}

std::optional<uint64_t> TimerQuery::resultNs() const {
  GLuint available = 0;
  while (!available) glGetQueryObjectuiv(handle_.id(), GL_QUERY_RESULT_AVAILABLE, &available);
  GLint disjoint = 0;
  glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
  glGetError();  // GL_GPU_DISJOINT_EXT is unknown on desktop GL; that is not disjoint.
  if (disjoint) return std::nullopt;
  GLuint ns = 0;
  glGetQueryObjectuiv(handle_.id(), GL_QUERY_RESULT, &ns);
  return static_cast<uint64_t>(ns);
}

// --- State --------------------------------------------------------------------------------

void apply(const PipelineState& s) {
  if (s.depthTest == DepthTest::Off) {
    glDisable(GL_DEPTH_TEST);
  } else {
    glEnable(GL_DEPTH_TEST);
    GLenum f = GL_LESS;
    switch (s.depthTest) {
      case DepthTest::Less:
        f = GL_LESS;
        break;
      case DepthTest::LessEqual:
        f = GL_LEQUAL;
        break;
      case DepthTest::Equal:
        f = GL_EQUAL;
        break;
      case DepthTest::Always:
        f = GL_ALWAYS;
        break;
      case DepthTest::Off:
        break;
    }
    glDepthFunc(f);
  }
  glDepthMask(s.depthWrite ? GL_TRUE : GL_FALSE);
  switch (s.blend) {
    case Blend::None:
      glDisable(GL_BLEND);
      break;
    case Blend::Additive:
      glEnable(GL_BLEND);
      glBlendEquation(GL_FUNC_ADD);
      glBlendFunc(GL_ONE, GL_ONE);
      break;
    case Blend::Alpha:
      glEnable(GL_BLEND);
      glBlendEquation(GL_FUNC_ADD);
      glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
      break;
    case Blend::PremultipliedAlpha:
      glEnable(GL_BLEND);
      glBlendEquation(GL_FUNC_ADD);
      glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
      break;
    case Blend::Multiply:
      glEnable(GL_BLEND);
      glBlendEquation(GL_FUNC_ADD);
      glBlendFuncSeparate(GL_ZERO, GL_SRC_COLOR, GL_ONE, GL_ONE);
      break;
    case Blend::ConstantMix:
      glEnable(GL_BLEND);
      glBlendEquation(GL_FUNC_ADD);
      glBlendColor(0.0f, 0.0f, 0.0f, s.blendWeight);
      glBlendFunc(GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA);
      break;
  }
  switch (s.cull) {
    case Cull::None:
      glDisable(GL_CULL_FACE);
      break;
    case Cull::Back:
      glEnable(GL_CULL_FACE);
      glCullFace(GL_BACK);
      break;
    case Cull::Front:
      glEnable(GL_CULL_FACE);
      glCullFace(GL_FRONT);
      break;
  }
  glFrontFace(s.frontFaceClockwise ? GL_CW : GL_CCW);
  const GLboolean c = s.colorWrite ? GL_TRUE : GL_FALSE;
  glColorMask(c, c, c, c);
  if (s.polygonOffsetFactor != 0.0f || s.polygonOffsetUnits != 0.0f) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(s.polygonOffsetFactor, s.polygonOffsetUnits);
  } else {
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
}

void setViewport(int x, int y, int width, int height) {
  glViewport(x, y, width, height);
}

void setScissor(int x, int y, int width, int height) {
  glEnable(GL_SCISSOR_TEST);
  glScissor(x, y, width, height);
}

void disableScissor() {
  glDisable(GL_SCISSOR_TEST);
}

void clearColor(float r, float g, float b, float a) {
  glClearColor(r, g, b, a);
  glClear(GL_COLOR_BUFFER_BIT);
}

void clearDepth(float depth) {
  glDepthMask(GL_TRUE);
  glClearDepthf(depth);
  glClear(GL_DEPTH_BUFFER_BIT);
}

void clearStencil() {
  glStencilMask(0xFF);
  glClearStencil(0);
  glClear(GL_STENCIL_BUFFER_BIT);
}

void setStencil(StencilMode mode) {
  switch (mode) {
    case StencilMode::Off:
      glDisable(GL_STENCIL_TEST);
      return;
    case StencilMode::SkipMarked:
      glEnable(GL_STENCIL_TEST);
      glStencilFunc(GL_EQUAL, 0, 0xFF);
      glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
      glStencilMask(0);
      return;
    case StencilMode::Mark:
      glEnable(GL_STENCIL_TEST);
      glStencilFunc(GL_ALWAYS, 1, 0xFF);
      glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
      glStencilMask(0xFF);
      return;
  }
}

void clearBufferFloat(int index, float r, float g, float b, float a) {
  const float v[4] = {r, g, b, a};
  glClearBufferfv(GL_COLOR, index, v);
}

void finish() {
  glFinish();
}
void flush() {
  glFlush();
}

TransformFeedback TransformFeedback::create() {
  GLuint id = 0;
  glGenTransformFeedbacks(1, &id);
  TransformFeedback t;
  t.handle_ = Handle<deleteTransformFeedback>(id);
  return t;
}

void TransformFeedback::capture(const VertexArray& vao, int count,
                                std::span<const Buffer* const> outputs) const {
  // WebGL refuses a buffer bound for feedback and as an attribute of the bound VAO at once:
  // `vao` reads other buffers, and the outputs are unbound again before anyone draws them.
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, handle_.id());
  for (size_t i = 0; i < outputs.size(); ++i) {
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLuint>(i), outputs[i]->id());
  }
  glEnable(GL_RASTERIZER_DISCARD);
  vao.bind();
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, count);
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  for (size_t i = 0; i < outputs.size(); ++i) {
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLuint>(i), 0);
  }
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, 0);
  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
}

}  // namespace penumbra::gl
