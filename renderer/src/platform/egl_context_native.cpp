// Headless EGL contexts: the Mesa surfaceless platform (default) and the EGL device platform
// (fallback; also how a real GPU is reached on a machine without a display). Both render only
// into framebuffer objects, so no surface is ever created.
#define EGL_NO_X11
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string>
#include <vector>

#include "platform/backends.h"

namespace penumbra::platform {
namespace {

std::string eglErrorName(EGLint e) {
  switch (e) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_CONTEXT_LOST:
      return "EGL_CONTEXT_LOST";
    default:
      return "EGL error " + std::to_string(e);
  }
}

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  }
  return false;
}

class EglContext final : public GlContext {
 public:
  EglContext(EGLDisplay display, EGLContext context, bool device)
      : display_(display), context_(context), device_(device) {}
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    // The display is shared process-wide by Mesa; terminating it would break other contexts.
  }
  GlBackend backend() const override {
    return device_ ? GlBackend::EglDevice : GlBackend::EglSurfaceless;
  }
  std::string description() const override { return description_; }
  Status makeCurrent() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      return makeError("eglMakeCurrent failed: " + eglErrorName(eglGetError()));
    }
    // Reload: another backend (OSMesa) may have replaced the process-wide entry points.
    if (!loadGlFunctions(reinterpret_cast<GetProcFn>(&eglGetProcAddress))) {
      return makeError("could not load the OpenGL ES 3.0 entry points");
    }
    return {};
  }
  void setDescription(std::string d) { description_ = std::move(d); }

 private:
  EGLDisplay display_;
  EGLContext context_;
  bool device_;
  std::string description_;
};

Result<EGLDisplay> openDisplay(bool device) {
  const char* clientExt = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!device) {
    if (!hasExtension(clientExt, "EGL_MESA_platform_surfaceless")) {
      return makeError("EGL_MESA_platform_surfaceless not supported");
    }
    EGLDisplay d =
        eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d == EGL_NO_DISPLAY)
      return makeError("no surfaceless display: " + eglErrorName(eglGetError()));
    return d;
  }
  if (!hasExtension(clientExt, "EGL_EXT_platform_device")) {
    return makeError("EGL_EXT_platform_device not supported");
  }
  auto queryDevices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  if (!queryDevices) return makeError("eglQueryDevicesEXT missing");
  EGLDeviceEXT devices[16];
  EGLint count = 0;
  if (!queryDevices(16, devices, &count) || count == 0) return makeError("no EGL devices");
  std::string why;
  for (EGLint i = 0; i < count; ++i) {
    EGLDisplay d = eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
    if (d == EGL_NO_DISPLAY) continue;
    EGLint major = 0, minor = 0;
    if (eglInitialize(d, &major, &minor)) return d;
    why = eglErrorName(eglGetError());
  }
  return makeError("no EGL device could be initialised" + (why.empty() ? "" : ": " + why));
}

}  // namespace

Result<std::unique_ptr<GlContext>> createEglContext(bool device) {
  auto display = openDisplay(device);
  if (!display) return display.error();
  EGLDisplay dpy = *display;
  EGLint major = 0, minor = 0;
  if (!eglInitialize(dpy, &major, &minor)) {
    return makeError("eglInitialize failed: " + eglErrorName(eglGetError()));
  }
  if (!eglBindAPI(EGL_OPENGL_ES_API)) return makeError("eglBindAPI(EGL_OPENGL_ES_API) failed");
  // No surface will be created: EGL_SURFACE_TYPE 0 matches every config (the default asks
  // for window support, which the surfaceless platform does not have).
  const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_SURFACE_TYPE, 0,
                                  EGL_NONE};
  EGLConfig config = nullptr;
  EGLint numConfigs = 0;
  if (!eglChooseConfig(dpy, configAttribs, &config, 1, &numConfigs) || numConfigs == 0) {
    return makeError("no EGL config with OpenGL ES 3 support");
  }
  const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0,
                                   EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, contextAttribs);
  if (ctx == EGL_NO_CONTEXT) {
    return makeError("eglCreateContext (ES 3.0) failed: " + eglErrorName(eglGetError()));
  }
  auto context = std::make_unique<EglContext>(dpy, ctx, device);
  if (auto st = context->makeCurrent(); !st) return st.error();
  applyCommonState(false);
  context->setDescription(std::string(device ? "EGL device" : "EGL surfaceless") + ": " +
                          currentGlDescription());
  return std::unique_ptr<GlContext>(std::move(context));
}

}  // namespace penumbra::platform
