// Move-only owners of the remaining GL object kinds: Buffer, VertexArray, Renderbuffer,
// Framebuffer and TimerQuery. Renderer logic uses these (and Texture2D/TextureCube/Program)
// instead of raw GL calls.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "gl/handle.h"
#include "gl/memory.h"
#include "gl/texture.h"
#include "penumbra/error.h"

namespace penumbra::gl {

// Feedback: vertex data that a transform feedback rewrites (a played pose's positions, normals
// and tangents), read by draws like Vertex.
enum class BufferKind { Vertex, Index, Uniform, Feedback };

class Buffer {
 public:
  Buffer() = default;
  static Result<Buffer> create(BufferKind kind, std::span<const uint8_t> data);
  template <class T>
  static Result<Buffer> create(BufferKind kind, std::span<const T> data) {
    return create(kind, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(data.data()),
                                                 data.size_bytes()));
  }
  void update(size_t offset, std::span<const uint8_t> data);
  void bind() const;
  GLuint id() const { return handle_.id(); }
  size_t size() const { return size_; }
  BufferKind kind() const { return kind_; }

 private:
  Handle<deleteBuffer> handle_;
  MemoryCharge memory_;
  BufferKind kind_ = BufferKind::Vertex;
  size_t size_ = 0;
};

enum class AttribType { Float, UInt8, UInt16, Int8, Int16 };
enum class IndexType { UInt8, UInt16, UInt32 };
enum class Primitive { Triangles, TriangleStrip, Lines, Points };

class VertexArray {
 public:
  VertexArray() = default;
  static VertexArray create();
  // Describes attribute `location` read from `buffer` (which must outlive the draws).
  void setAttribute(int location, const Buffer& buffer, int components, AttribType type,
                    bool normalized, int stride, size_t offset);
  // A constant value for an attribute location with no buffer (e.g. missing vertex colours).
  void setConstant(int location, float x, float y, float z, float w);
  void setIndexBuffer(const Buffer& buffer, IndexType type);
  // Per-instance rows of an affine 3x4 matrix at locations location..location+2, read from
  // `buffer` at `offset` (three vec4 per instance, advancing every `divisor` instances), or,
  // with no buffer, the identity as constant values. Changes the VAO, so each draw sets it.
  void setInstanceRows(int location, const Buffer* buffer, size_t offset, int divisor) const;
  void bind() const;
  // Draws with the bound program: indexed when an index buffer is set, else arrays.
  void draw(Primitive mode, int count, size_t firstOrByteOffset = 0) const;
  // The same, `instances` times (gl_InstanceID 0..instances-1).
  void drawInstanced(Primitive mode, int count, int instances, size_t firstOrByteOffset = 0) const;
  GLuint id() const { return handle_.id(); }

 private:
  Handle<deleteVertexArray> handle_;
  bool indexed_ = false;
  IndexType indexType_ = IndexType::UInt32;
  std::vector<std::pair<int, std::array<float, 4>>> constants_;
};

// A transform feedback object: captures a vertex shader's outputs (Program::build's `feedback`
// varyings, one buffer each) into buffers, with rasterization off. Playback poses skinned and
// morphed geometry once per pose this way, and every pass then draws the posed buffers.
class TransformFeedback {
 public:
  TransformFeedback() = default;
  static TransformFeedback create();
  // Runs the program in use over vertices 0..count-1 of `vao` (as points), writing its feedback
  // varyings, in order, into `outputs` (each at least count times the varying's size).
  void capture(const VertexArray& vao, int count, std::span<const Buffer* const> outputs) const;

 private:
  Handle<deleteTransformFeedback> handle_;
};

class Renderbuffer {
 public:
  Renderbuffer() = default;
  static Result<Renderbuffer> create(int width, int height, PixelFormat format);
  GLuint id() const { return handle_.id(); }
  PixelFormat format() const { return format_; }
  int64_t bytes() const { return memory_.bytes(); }  // the GPU memory it holds (MemoryCharge)

 private:
  Handle<deleteRenderbuffer> handle_;
  MemoryCharge memory_;
  PixelFormat format_ = PixelFormat::Depth24;
};

class Framebuffer {
 public:
  Framebuffer() = default;
  static Framebuffer create();

  void attachColor(int index, const Texture2D& texture, int level = 0);
  void attachColor(int index, const TextureCube& cube, int face, int level);
  // One layer of a colour texture array.
  void attachColor(int index, const Texture2DArray& array, int layer);
  void attachDepth(const Texture2D& texture);
  // One layer of a depth texture array.
  void attachDepth(const Texture2DArray& array, int layer);
  void attachDepth(const Renderbuffer& renderbuffer);
  // One face (0..5, GL order) of a depth cube map: a point light's shadow.
  void attachDepth(const TextureCube& cube, int face);
  // Enables draw buffers 0..count-1.
  void setDrawBuffers(int count);
  // Complete, or an error naming the status (e.g. GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT).
  Status checkComplete() const;
  void bind() const;
  static void bindDefault();
  // Binds a framebuffer Penumbra does not own (a host's render target), by its GL name.
  static void bindExternal(GLuint id);

  // Copies colour attachment 0 of this framebuffer into `target`'s (same size and format,
  // nearest), within the scissor rectangle when the scissor test is on. Leaves `target` bound.
  void blitColorTo(const Framebuffer& target, int width, int height) const;
  // Reads RGBA float pixels of colour attachment `index` (row 0 = bottom, GL order).
  std::vector<float> readRgbaFloat(int index, int x, int y, int width, int height) const;
  std::vector<uint8_t> readRgba8(int index, int x, int y, int width, int height) const;
  GLuint id() const { return handle_.id(); }

 private:
  Handle<deleteFramebuffer> handle_;
};

// GPU time of the commands between begin() and end(), where the context offers timer queries
// (EXT_disjoint_timer_query on ES/WebGL, core on desktop GL). Unavailable elsewhere.
class TimerQuery {
 public:
  TimerQuery() = default;
  static std::optional<TimerQuery> create(bool supported);
  void begin();
  void end();
  // Nanoseconds once the result is available (blocks until then); nullopt when disjoint.
  std::optional<uint64_t> resultNs() const;

 private:
  Handle<deleteQuery> handle_;
};

// Fixed-function state of a pass, applied as a whole so passes never inherit stale state.
// ConstantMix: dst = src w + dst (1 - w) with w = PipelineState::blendWeight (a running mean
// written in place, one draw per weight).
// Multiply: colour = source x destination, alpha = source + destination (a shadow catcher's
// darkening, and its coverage over a transparent background).
enum class Blend { None, Additive, Alpha, PremultipliedAlpha, ConstantMix, Multiply };
enum class Cull { None, Back, Front };
enum class DepthTest { Off, Less, LessEqual, Equal, Always };

struct PipelineState {
  DepthTest depthTest = DepthTest::Less;
  bool depthWrite = true;
  Blend blend = Blend::None;
  Cull cull = Cull::Back;
  bool frontFaceClockwise = false;  // mirrored transforms flip the winding
  bool colorWrite = true;
  float polygonOffsetFactor = 0.0f;  // slope-scaled depth bias (shadow maps)
  float polygonOffsetUnits = 0.0f;
  float blendWeight = 1.0f;  // Blend::ConstantMix only
};

void apply(const PipelineState& state);
void setViewport(int x, int y, int width, int height);
// Limits drawing and clears to a rectangle (a band of a frame drawn in parts) until
// disableScissor(); Penumbra's passes otherwise run with the scissor test off.
void setScissor(int x, int y, int width, int height);
void disableScissor();
void clearColor(float r, float g, float b, float a);
void clearDepth(float depth = 1.0f);
// The stencil test of the frame's depth-stencil buffer, which marks the tiles an automatic view
// no longer shades (Renderer::Impl::skipTiles). Off: no test (Penumbra's default). SkipMarked:
// draws only where the stencil is 0, writing nothing. Mark: writes 1 wherever a fragment is
// drawn. Framebuffers without a stencil buffer pass the test.
enum class StencilMode { Off, SkipMarked, Mark };
void setStencil(StencilMode mode);
// Clears the bound framebuffer's stencil to 0 (within the scissor, when on).
void clearStencil();
// Clears float colour attachment `index` of the bound framebuffer.
void clearBufferFloat(int index, float r, float g, float b, float a);
// Waits for the GPU (timing, read-back).
void finish();
void flush();

}  // namespace penumbra::gl
