#include "gl/capabilities.h"

#include <cstring>
#include <sstream>

#include "gl/errors.h"
#include "gl/objects.h"

namespace penumbra::gl {
namespace {

bool hasExtension(const char* name) {
  GLint n = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i) {
    const auto* e =
        reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
    if (e && std::strcmp(e, name) == 0) return true;
  }
  return false;
}

bool renderable(PixelFormat format) {
  auto tex =
      Texture2D::create({.width = 4,
                         .height = 4,
                         .format = format,
                         .levels = 1,
                         .sampler = {.minFilter = Filter::Nearest, .magFilter = Filter::Nearest}});
  if (!tex) {
    clearErrors();
    return false;
  }
  Framebuffer fb = Framebuffer::create();
  fb.attachColor(0, *tex);
  bool ok = static_cast<bool>(fb.checkComplete());
  Framebuffer::bindDefault();
  clearErrors();
  return ok;
}

std::string str(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "?";
}

}  // namespace

Capabilities queryCapabilities(bool desktopGl, const CapabilityOptions& options) {
  Capabilities c;
  c.version = str(GL_VERSION);
  c.renderer = str(GL_RENDERER);
  c.desktopGl = desktopGl;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &c.maxTextureSize);
  glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &c.maxCubeMapSize);
  glGetIntegerv(GL_MAX_DRAW_BUFFERS, &c.maxDrawBuffers);
  c.colorBufferFloat = renderable(PixelFormat::RGBA32F);
  c.colorBufferHalfFloat = renderable(PixelFormat::RGBA16F);
  // Desktop GL has these in core; ES and WebGL need the extensions.
  c.floatLinear = desktopGl || hasExtension("GL_OES_texture_float_linear") ||
                  hasExtension("OES_texture_float_linear");
  c.floatBlend = desktopGl || hasExtension("GL_EXT_float_blend") || hasExtension("EXT_float_blend");
  c.timerQuery = desktopGl || hasExtension("GL_EXT_disjoint_timer_query") ||
                 hasExtension("EXT_disjoint_timer_query_webgl2");
  clearErrors();

  const bool use32 = c.colorBufferFloat && !options.forceHalfFloat;
  if (use32) {
    c.accumulationFormat = PixelFormat::RGBA32F;
  } else if (c.colorBufferHalfFloat) {
    c.accumulationFormat = PixelFormat::RGBA16F;
    c.fallbacks.push_back(options.forceHalfFloat
                              ? "RGBA16F accumulation (forced)"
                              : "RGBA32F is not renderable: accumulating in RGBA16F");
  } else {
    c.accumulationFormat = PixelFormat::RGBA8;
    c.fallbacks.push_back(
        "no float colour buffers: accumulating in RGBA8 (banding; fewer frames recommended)");
  }
  if (!c.floatLinear) {
    c.fallbacks.push_back("32-bit float textures are not filterable: HDR textures use RGB16F");
  }
  return c;
}

std::string Capabilities::report() const {
  std::ostringstream s;
  s << "GL: " << version << " on " << renderer << "\n"
    << "  RGBA32F renderable: " << (colorBufferFloat ? "yes" : "no") << "\n"
    << "  RGBA16F renderable: " << (colorBufferHalfFloat ? "yes" : "no") << "\n"
    << "  float linear filtering: " << (floatLinear ? "yes" : "no") << "\n"
    << "  float blending: " << (floatBlend ? "yes" : "no") << "\n"
    << "  timer queries: " << (timerQuery ? "yes" : "no") << "\n"
    << "  max texture size: " << maxTextureSize << ", max cube size: " << maxCubeMapSize
    << ", draw buffers: " << maxDrawBuffers << "\n"
    << "  accumulation format: " << formatName(accumulationFormat) << "\n";
  for (const auto& f : fallbacks) s << "  fallback: " << f << "\n";
  return s.str();
}

}  // namespace penumbra::gl
