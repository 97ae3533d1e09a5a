// WebGL2 on a canvas, through Emscripten's HTML5 API. The float-target extensions are enabled
// here once, so the capability report sees them.
#include <emscripten/html5.h>

#include <string>

#include "gl/gl.h"
#include "platform/backends.h"

namespace penumbra::platform {
namespace {

class WebGlContext final : public GlContext {
 public:
  explicit WebGlContext(EMSCRIPTEN_WEBGL_CONTEXT_HANDLE handle) : handle_(handle) {}
  ~WebGlContext() override { emscripten_webgl_destroy_context(handle_); }
  GlBackend backend() const override { return GlBackend::WebGL2; }
  std::string description() const override { return description_; }
  Status makeCurrent() override {
    if (emscripten_webgl_make_context_current(handle_) != EMSCRIPTEN_RESULT_SUCCESS) {
      return makeError("emscripten_webgl_make_context_current failed");
    }
    return {};
  }
  void setDescription(std::string d) { description_ = std::move(d); }

 private:
  EMSCRIPTEN_WEBGL_CONTEXT_HANDLE handle_;
  std::string description_;
};

}  // namespace

int loadGlFunctions(GetProcFn) {
  return 30000;
}

std::string currentGlDescription() {
  auto str = [](GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return std::string(s ? s : "?");
  };
  return str(GL_VERSION) + " (" + str(GL_RENDERER) + ")";
}

void applyCommonState(bool) {
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
}

Result<std::unique_ptr<GlContext>> createWebGlContext(const ContextOptions& options) {
  EmscriptenWebGLContextAttributes attrs;
  emscripten_webgl_init_context_attributes(&attrs);
  attrs.majorVersion = 2;
  attrs.minorVersion = 0;
  // An alpha channel for RenderSettings::transparentBackground (the page shows through);
  // tone mapping writes straight alpha, 1 where the background is drawn.
  attrs.alpha = true;
  attrs.premultipliedAlpha = false;
  attrs.depth = true;
  attrs.antialias = false;  // anti-aliasing comes from progressive sub-pixel jitter
  attrs.preserveDrawingBuffer = options.preserveDrawingBuffer;
  attrs.powerPreference = EM_WEBGL_POWER_PREFERENCE_HIGH_PERFORMANCE;
  EMSCRIPTEN_WEBGL_CONTEXT_HANDLE handle =
      emscripten_webgl_create_context(options.canvasSelector.c_str(), &attrs);
  if (handle <= 0) {
    return makeError("WebGL2 is not available on canvas '" + options.canvasSelector + "' (code " +
                     std::to_string(static_cast<long>(handle)) + ")");
  }
  auto context = std::make_unique<WebGlContext>(handle);
  if (auto st = context->makeCurrent(); !st) return st.error();
  for (const char* ext :
       {"EXT_color_buffer_float", "EXT_color_buffer_half_float", "OES_texture_float_linear",
        "EXT_float_blend", "EXT_disjoint_timer_query_webgl2"}) {
    emscripten_webgl_enable_extension(handle, ext);
  }
  applyCommonState(false);
  context->setDescription("WebGL2: " + currentGlDescription());
  return std::unique_ptr<GlContext>(std::move(context));
}

Result<std::unique_ptr<GlContext>> createEglContext(bool) {
  return makeError("EGL exists only in native builds");
}
Result<std::unique_ptr<GlContext>> createOsMesaContext() {
  return makeError("OSMesa exists only in native builds");
}

}  // namespace penumbra::platform
