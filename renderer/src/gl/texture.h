// Texture2D, Texture2DArray and TextureCube: move-only owners of GL textures with explicit formats,
// mip levels and sampling state. Formats are limited to what OpenGL ES 3.0 / WebGL2 offer.
#pragma once

#include <cstdint>
#include <vector>

#include "gl/handle.h"
#include "gl/memory.h"
#include "penumbra/error.h"

namespace penumbra::gl {

enum class PixelFormat {
  RGBA8,         // UNORM, colour textures stored linear
  SRGB8_ALPHA8,  // colour textures in sRGB (base colour, emissive)
  RGBA16F,
  RGBA32F,
  RGB16F,  // filterable HDR textures (environment)
  RG16F,
  R32F,
  RGB10A2,          // UNORM, 10 bits a colour channel (colour-renderable in ES 3.0 / WebGL2)
  Depth24,          // DEPTH_COMPONENT24
  Depth32F,         // DEPTH_COMPONENT32F
  Depth24Stencil8,  // DEPTH24_STENCIL8 (renderbuffers: the frame's depth and tile mask)
};

enum class DataType { UInt8, Float, HalfFloat };
enum class Filter { Nearest, Linear, LinearMipLinear, NearestMipNearest };
enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };

const char* formatName(PixelFormat format);
int bytesPerPixel(PixelFormat format);
bool isDepthFormat(PixelFormat format);

struct SamplerState {
  Filter minFilter = Filter::Linear;
  Filter magFilter = Filter::Linear;
  Wrap wrapS = Wrap::ClampToEdge;
  Wrap wrapT = Wrap::ClampToEdge;
  // Depth textures only: sample with a comparison (sampler2DShadow, hardware PCF).
  bool depthCompare = false;
};

struct TextureDesc {
  int width = 0;
  int height = 0;  // ignored for cube maps (faces are square)
  PixelFormat format = PixelFormat::RGBA8;
  int levels = 1;  // mip levels allocated (immutable storage)
  SamplerState sampler;
};

class Texture2D {
 public:
  Texture2D() = default;
  // Allocates immutable storage for all levels. Errors on absurd sizes or GL out-of-memory.
  static Result<Texture2D> create(const TextureDesc& desc);

  // A block-compressed texture (`internalFormat` a GL compressed format the context supports,
  // e.g. ASTC 4x4), one entry of `levels` per mip level from 0, each that level's blocks. Its
  // format() is the uncompressed one it decodes to (`decoded`).
  static Result<Texture2D> createCompressed(int width, int height, uint32_t internalFormat,
                                            PixelFormat decoded,
                                            const std::vector<std::vector<uint8_t>>& levels,
                                            const SamplerState& sampler);

  // Uploads a whole level; `data` holds width x height pixels of the format's channels.
  void upload(int level, const void* data, DataType type);
  void generateMipmaps();
  void setSampler(const SamplerState& sampler);
  void bind(int unit) const;

  GLuint id() const { return handle_.id(); }
  int width() const { return desc_.width; }
  int height() const { return desc_.height; }
  int levels() const { return desc_.levels; }
  PixelFormat format() const { return desc_.format; }
  explicit operator bool() const { return static_cast<bool>(handle_); }
  int64_t bytes() const { return memory_.bytes(); }  // the GPU memory it holds (MemoryCharge)

 private:
  // Immutable storage with `desc`'s levels and sampler, in `internalFormat`, left bound.
  static Texture2D allocate(const TextureDesc& desc, GLenum internalFormat);

  Handle<deleteTexture> handle_;
  MemoryCharge memory_;
  TextureDesc desc_;
};

// Layers of equal size and format behind one sampler (sampler2DArray / sampler2DArrayShadow):
// one texture unit for what would otherwise take one per texture.
class Texture2DArray {
 public:
  Texture2DArray() = default;
  static Result<Texture2DArray> create(const TextureDesc& desc, int layers);

  // Uploads level 0 of one layer (width x height pixels of the format's channels).
  void upload(int layer, const void* data, DataType type);
  void generateMipmaps();
  void bind(int unit) const;

  GLuint id() const { return handle_.id(); }
  int width() const { return desc_.width; }
  int height() const { return desc_.height; }
  int layers() const { return layers_; }
  PixelFormat format() const { return desc_.format; }
  explicit operator bool() const { return static_cast<bool>(handle_); }
  int64_t bytes() const { return memory_.bytes(); }  // the GPU memory it holds (MemoryCharge)

 private:
  Handle<deleteTexture> handle_;
  MemoryCharge memory_;
  TextureDesc desc_;
  int layers_ = 0;
};

class TextureCube {
 public:
  TextureCube() = default;
  // desc.width is the face size; desc.levels the number of explicit mip levels.
  static Result<TextureCube> create(const TextureDesc& desc);

  // face: 0..5 in GL order +X, -X, +Y, -Y, +Z, -Z.
  void upload(int face, int level, const void* data, DataType type);
  void generateMipmaps();
  void setSampler(const SamplerState& sampler);
  void bind(int unit) const;

  GLuint id() const { return handle_.id(); }
  int size() const { return desc_.width; }
  int levels() const { return desc_.levels; }
  PixelFormat format() const { return desc_.format; }
  explicit operator bool() const { return static_cast<bool>(handle_); }
  int64_t bytes() const { return memory_.bytes(); }  // the GPU memory it holds (MemoryCharge)

 private:
  Handle<deleteTexture> handle_;
  MemoryCharge memory_;
  TextureDesc desc_;
};

// Number of mip levels of a full chain for a size.
int fullMipCount(int width, int height);

}  // namespace penumbra::gl
