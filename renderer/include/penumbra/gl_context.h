// GlContext: a current OpenGL ES 3.0-class (WebGL2-equivalent) context. Natively it is headless
// (EGL surfaceless on Mesa by default, the EGL device platform as fallback, or OSMesa); in the
// browser it is a WebGL2 context on a canvas. Everything else in Penumbra renders into
// framebuffer objects and never touches a window system.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "penumbra/error.h"

namespace penumbra {

enum class GlBackend {
  Auto,            // PENUMBRA_GL if set, else EGL surfaceless, then EGL device, then OSMesa
  EglSurfaceless,  // EGL_PLATFORM_SURFACELESS_MESA
  EglDevice,       // EGL_EXT_platform_device (e.g. EGL_MESA_device_software or a GPU)
  OSMesa,          // Mesa's off-screen desktop GL 4.5 core (runs our ES 3.00 shaders)
  WebGL2,          // Emscripten, a canvas in the page
  Host,            // a context the host application created and made current (adoptCurrent)
};

const char* backendName(GlBackend backend);
// Parses "auto", "egl", "egl-device", "osmesa", "webgl2" (case-insensitive).
Result<GlBackend> parseBackend(std::string_view name);

struct ContextOptions {
  GlBackend backend = GlBackend::Auto;
  std::string canvasSelector = "#canvas";  // WebGL2 only
  bool preserveDrawingBuffer = true;       // WebGL2 only: screenshots read the canvas
};

class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Creates a context and makes it current, with the GL entry points loaded. When no backend
  // works, the error says in one line which backends were tried and why each failed.
  static Result<std::unique_ptr<GlContext>> create(const ContextOptions& options = {});

  // For a host that draws Penumbra into its own framebuffer: wraps the OpenGL ES 3.0 (or
  // desktop GL 3.3+ with ES 3 compatibility) context the host made current, loading the entry
  // points through `getProcAddress` (eglGetProcAddress when null). The wrapper does not own,
  // make current or destroy the host's context. Create the Renderer with
  // RendererOptions::preserveHostState so it leaves the host's GL state as it found it.
  // Native builds only.
  using GetProcAddress = void (*(*)(const char*))();
  static Result<std::unique_ptr<GlContext>> adoptCurrent(GetProcAddress getProcAddress = nullptr,
                                                         bool desktopGl = false);

  // False when the machine exposes no GPU device (no DRM render node, no NVIDIA device node):
  // then every context is a software rasterizer, and a tool that would only use the GPU when
  // it is faster need not create one. True in the browser (the page cannot tell).
  static bool hardwareGpuPresent();

  virtual GlBackend backend() const = 0;
  // "EGL surfaceless: OpenGL ES 3.0 Mesa 22.3.6 (llvmpipe ...)" and the like.
  virtual std::string description() const = 0;
  virtual Status makeCurrent() = 0;
  // True when the API is desktop GL (OSMesa): some ES-only behaviour must be switched on.
  virtual bool isDesktopGl() const { return false; }

 protected:
  GlContext() = default;
};

}  // namespace penumbra
