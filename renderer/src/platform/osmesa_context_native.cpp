// OSMesa: Mesa's off-screen software context. It offers desktop GL 4.5 core only (no GLES
// profile), which still compiles our `#version 300 es` shaders through ARB_ES3_compatibility.
// Chosen with PENUMBRA_GL=osmesa or --gl osmesa, and the last native fallback.
#include <GL/osmesa.h>

#include <string>
#include <vector>

#include "platform/backends.h"

namespace penumbra::platform {
namespace {

class OsMesaContext final : public GlContext {
 public:
  explicit OsMesaContext(OSMesaContext ctx) : ctx_(ctx), buffer_(4 * 4 * 4) {}
  ~OsMesaContext() override { OSMesaDestroyContext(ctx_); }
  GlBackend backend() const override { return GlBackend::OSMesa; }
  std::string description() const override { return description_; }
  bool isDesktopGl() const override { return true; }
  Status makeCurrent() override {
    // OSMesa needs a colour buffer to be current; we render only into FBOs, so 4x4 is enough.
    if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 4, 4)) {
      return makeError("OSMesaMakeCurrent failed");
    }
    if (!loadGlFunctions(reinterpret_cast<GetProcFn>(&OSMesaGetProcAddress))) {
      return makeError("could not load the GL entry points through OSMesa");
    }
    return {};
  }
  void setDescription(std::string d) { description_ = std::move(d); }

 private:
  OSMesaContext ctx_;
  std::vector<unsigned char> buffer_;
  std::string description_;
};

}  // namespace

Result<std::unique_ptr<GlContext>> createOsMesaContext() {
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         24,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         3,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         3,
                         0};
  OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!ctx) return makeError("OSMesaCreateContextAttribs (GL 3.3 core) failed");
  auto context = std::make_unique<OsMesaContext>(ctx);
  if (auto st = context->makeCurrent(); !st) return st.error();
  applyCommonState(true);
  context->setDescription("OSMesa: " + currentGlDescription());
  return std::unique_ptr<GlContext>(std::move(context));
}

// Not available natively.
Result<std::unique_ptr<GlContext>> createWebGlContext(const ContextOptions&) {
  return makeError("WebGL2 exists only in the browser build");
}

}  // namespace penumbra::platform
