#include "gl/texture.h"

#include <cstdio>

#include <algorithm>
#include <string>

#include "gl/errors.h"

namespace penumbra::gl {
namespace {

struct FormatInfo {
  GLenum internal;
  GLenum format;
  GLenum type;
  int bytes;
};

FormatInfo info(PixelFormat f) {
  switch (f) {
    case PixelFormat::RGBA8:
      return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, 4};
    case PixelFormat::SRGB8_ALPHA8:
      return {GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE, 4};
    case PixelFormat::RGBA16F:
      return {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT, 8};
    case PixelFormat::RGBA32F:
      return {GL_RGBA32F, GL_RGBA, GL_FLOAT, 16};
    case PixelFormat::RGB16F:
      return {GL_RGB16F, GL_RGB, GL_HALF_FLOAT, 6};
    case PixelFormat::RG16F:
      return {GL_RG16F, GL_RG, GL_HALF_FLOAT, 4};
    case PixelFormat::R32F:
      return {GL_R32F, GL_RED, GL_FLOAT, 4};
    case PixelFormat::RGB10A2:
      return {GL_RGB10_A2, GL_RGBA, GL_UNSIGNED_INT_2_10_10_10_REV, 4};
    case PixelFormat::Depth24:
      return {GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, 4};
    case PixelFormat::Depth32F:
      return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, 4};
    case PixelFormat::Depth24Stencil8:
      return {GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8, 4};
  }
  return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, 4};
}

GLenum uploadType(DataType t, PixelFormat f) {
  switch (t) {
    case DataType::UInt8:
      return GL_UNSIGNED_BYTE;
    case DataType::Float:
      return GL_FLOAT;
    case DataType::HalfFloat:
      return GL_HALF_FLOAT;
  }
  return info(f).type;
}

GLint glFilter(Filter f) {
  switch (f) {
    case Filter::Nearest:
      return GL_NEAREST;
    case Filter::Linear:
      return GL_LINEAR;
    case Filter::LinearMipLinear:
      return GL_LINEAR_MIPMAP_LINEAR;
    case Filter::NearestMipNearest:
      return GL_NEAREST_MIPMAP_NEAREST;
  }
  return GL_LINEAR;
}

GLint glWrap(Wrap w) {
  switch (w) {
    case Wrap::Repeat:
      return GL_REPEAT;
    case Wrap::ClampToEdge:
      return GL_CLAMP_TO_EDGE;
    case Wrap::MirroredRepeat:
      return GL_MIRRORED_REPEAT;
  }
  return GL_CLAMP_TO_EDGE;
}

void applySampler(GLenum target, const SamplerState& s) {
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, glFilter(s.minFilter));
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER,
                  s.magFilter == Filter::Nearest ? GL_NEAREST : GL_LINEAR);
  glTexParameteri(target, GL_TEXTURE_WRAP_S, glWrap(s.wrapS));
  glTexParameteri(target, GL_TEXTURE_WRAP_T, glWrap(s.wrapT));
  if (target == GL_TEXTURE_CUBE_MAP) {
    glTexParameteri(target, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  }
  if (s.depthCompare) {
    glTexParameteri(target, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(target, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  } else {
    glTexParameteri(target, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  }
}

Status validate(const TextureDesc& d, bool cube) {
  GLint maxSize = 0;
  glGetIntegerv(cube ? GL_MAX_CUBE_MAP_TEXTURE_SIZE : GL_MAX_TEXTURE_SIZE, &maxSize);
  const int h = cube ? d.width : d.height;
  if (d.width <= 0 || h <= 0 || d.width > maxSize || h > maxSize) {
    return makeError("texture size " + std::to_string(d.width) + "x" + std::to_string(h) +
                     " is outside 1.." + std::to_string(maxSize) + " (this GPU's limit)");
  }
  if (d.levels < 1 || d.levels > fullMipCount(d.width, h)) {
    return makeError("texture level count " + std::to_string(d.levels) + " is invalid for " +
                     std::to_string(d.width) + "x" + std::to_string(h));
  }
  return {};
}

}  // namespace

const char* formatName(PixelFormat format) {
  switch (format) {
    case PixelFormat::RGBA8:
      return "RGBA8";
    case PixelFormat::SRGB8_ALPHA8:
      return "SRGB8_ALPHA8";
    case PixelFormat::RGBA16F:
      return "RGBA16F";
    case PixelFormat::RGBA32F:
      return "RGBA32F";
    case PixelFormat::RGB16F:
      return "RGB16F";
    case PixelFormat::RG16F:
      return "RG16F";
    case PixelFormat::R32F:
      return "R32F";
    case PixelFormat::RGB10A2:
      return "RGB10_A2";
    case PixelFormat::Depth24:
      return "DEPTH_COMPONENT24";
    case PixelFormat::Depth32F:
      return "DEPTH_COMPONENT32F";
    case PixelFormat::Depth24Stencil8:
      return "DEPTH24_STENCIL8";
  }
  return "?";
}

int bytesPerPixel(PixelFormat format) {
  return info(format).bytes;
}
bool isDepthFormat(PixelFormat f) {
  return f == PixelFormat::Depth24 || f == PixelFormat::Depth32F ||
         f == PixelFormat::Depth24Stencil8;
}

int fullMipCount(int width, int height) {
  int n = 1;
  for (int s = std::max(width, height); s > 1; s >>= 1) ++n;
  return n;
}

Texture2D Texture2D::allocate(const TextureDesc& desc, GLenum internalFormat) {
  GLuint id = 0;
  glGenTextures(1, &id);
  Texture2D t;
  t.handle_ = Handle<deleteTexture>(id);
  t.desc_ = desc;
  glBindTexture(GL_TEXTURE_2D, id);
  glTexStorage2D(GL_TEXTURE_2D, desc.levels, internalFormat, desc.width, desc.height);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, desc.levels - 1);
  applySampler(GL_TEXTURE_2D, desc.sampler);
  return t;
}

Result<Texture2D> Texture2D::create(const TextureDesc& desc) {
  PN_TRY(validate(desc, false));
  beginAllocation();
  Texture2D t = allocate(desc, info(desc.format).internal);
  PN_TRY(checkAllocation(std::string("allocating a ") + std::to_string(desc.width) + "x" +
                    std::to_string(desc.height) + " " + formatName(desc.format) + " texture"));
  t.memory_ =
      MemoryCharge(storageBytes(desc.width, desc.height, desc.levels, bytesPerPixel(desc.format)));
  return t;
}

Result<Texture2D> Texture2D::createCompressed(int width, int height, uint32_t internalFormat,
                                              PixelFormat decoded,
                                              const std::vector<std::vector<uint8_t>>& levels,
                                              const SamplerState& sampler) {
  const TextureDesc desc{.width = width,
                         .height = height,
                         .format = decoded,
                         .levels = static_cast<int>(levels.size()),
                         .sampler = sampler};
  PN_TRY(validate(desc, false));
  beginAllocation();
  Texture2D t = allocate(desc, internalFormat);
  for (int level = 0; level < desc.levels; ++level) {
    const auto& blocks = levels[static_cast<size_t>(level)];
    glCompressedTexSubImage2D(GL_TEXTURE_2D, level, 0, 0, std::max(1, width >> level),
                              std::max(1, height >> level), internalFormat,
                              static_cast<GLsizei>(blocks.size()), blocks.data());
  }
  char hex[16];
  std::snprintf(hex, sizeof hex, "%X", internalFormat);
  PN_TRY(checkAllocation("uploading a " + std::to_string(width) + "x" + std::to_string(height) +
                    " compressed texture (format 0x" + hex + ")"));
  int64_t bytes = 0;
  for (const auto& blocks : levels) bytes += static_cast<int64_t>(blocks.size());
  t.memory_ = MemoryCharge(bytes);
  return t;
}

void Texture2D::upload(int level, const void* data, DataType type) {
  PN_CHECK(handle_ && level >= 0 && level < desc_.levels, "upload to a missing texture level");
  const FormatInfo fi = info(desc_.format);
  glBindTexture(GL_TEXTURE_2D, handle_.id());
  glTexSubImage2D(GL_TEXTURE_2D, level, 0, 0, std::max(1, desc_.width >> level),
                  std::max(1, desc_.height >> level), fi.format, uploadType(type, desc_.format),
                  data);
}

void Texture2D::generateMipmaps() {
  glBindTexture(GL_TEXTURE_2D, handle_.id());
  glGenerateMipmap(GL_TEXTURE_2D);
}

void Texture2D::setSampler(const SamplerState& sampler) {
  desc_.sampler = sampler;
  glBindTexture(GL_TEXTURE_2D, handle_.id());
  applySampler(GL_TEXTURE_2D, sampler);
}

void Texture2D::bind(int unit) const {
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_2D, handle_.id());
}

Result<Texture2DArray> Texture2DArray::create(const TextureDesc& desc, int layers) {
  PN_TRY(validate(desc, false));
  GLint maxLayers = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  if (layers < 1 || layers > maxLayers) {
    return makeError("texture array layer count " + std::to_string(layers) + " is outside 1.." +
                     std::to_string(maxLayers));
  }
  beginAllocation();
  GLuint id = 0;
  glGenTextures(1, &id);
  Texture2DArray t;
  t.handle_ = Handle<deleteTexture>(id);
  t.desc_ = desc;
  t.layers_ = layers;
  glBindTexture(GL_TEXTURE_2D_ARRAY, id);
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, desc.levels, info(desc.format).internal, desc.width,
                 desc.height, layers);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, desc.levels - 1);
  applySampler(GL_TEXTURE_2D_ARRAY, desc.sampler);
  PN_TRY(checkAllocation("allocating a " + std::to_string(desc.width) + "x" +
                    std::to_string(desc.height) + "x" + std::to_string(layers) + " " +
                    formatName(desc.format) + " texture array"));
  t.memory_ = MemoryCharge(
      storageBytes(desc.width, desc.height, desc.levels, bytesPerPixel(desc.format), layers));
  return t;
}

void Texture2DArray::upload(int layer, const void* data, DataType type) {
  PN_CHECK(handle_ && layer >= 0 && layer < layers_, "upload to a missing texture array layer");
  const FormatInfo fi = info(desc_.format);
  glBindTexture(GL_TEXTURE_2D_ARRAY, handle_.id());
  glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, desc_.width, desc_.height, 1, fi.format,
                  uploadType(type, desc_.format), data);
}

void Texture2DArray::generateMipmaps() {
  glBindTexture(GL_TEXTURE_2D_ARRAY, handle_.id());
  glGenerateMipmap(GL_TEXTURE_2D_ARRAY);
}

void Texture2DArray::bind(int unit) const {
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_2D_ARRAY, handle_.id());
}

Result<TextureCube> TextureCube::create(const TextureDesc& desc) {
  PN_TRY(validate(desc, true));
  beginAllocation();
  GLuint id = 0;
  glGenTextures(1, &id);
  TextureCube t;
  t.handle_ = Handle<deleteTexture>(id);
  t.desc_ = desc;
  t.desc_.height = desc.width;
  glBindTexture(GL_TEXTURE_CUBE_MAP, id);
  glTexStorage2D(GL_TEXTURE_CUBE_MAP, desc.levels, info(desc.format).internal, desc.width,
                 desc.width);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, desc.levels - 1);
  applySampler(GL_TEXTURE_CUBE_MAP, desc.sampler);
  PN_TRY(checkAllocation("allocating a " + std::to_string(desc.width) + " px cube map"));
  t.memory_ = MemoryCharge(
      storageBytes(desc.width, desc.width, desc.levels, bytesPerPixel(desc.format), 6));
  return t;
}

void TextureCube::upload(int face, int level, const void* data, DataType type) {
  PN_CHECK(handle_ && face >= 0 && face < 6 && level >= 0 && level < desc_.levels,
           "upload to a missing cube face or level");
  const FormatInfo fi = info(desc_.format);
  const int s = std::max(1, desc_.width >> level);
  glBindTexture(GL_TEXTURE_CUBE_MAP, handle_.id());
  glTexSubImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, level, 0, 0, s, s, fi.format,
                  uploadType(type, desc_.format), data);
}

void TextureCube::generateMipmaps() {
  glBindTexture(GL_TEXTURE_CUBE_MAP, handle_.id());
  glGenerateMipmap(GL_TEXTURE_CUBE_MAP);
}

void TextureCube::setSampler(const SamplerState& sampler) {
  desc_.sampler = sampler;
  glBindTexture(GL_TEXTURE_CUBE_MAP, handle_.id());
  applySampler(GL_TEXTURE_CUBE_MAP, sampler);
}

void TextureCube::bind(int unit) const {
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_CUBE_MAP, handle_.id());
}

}  // namespace penumbra::gl
