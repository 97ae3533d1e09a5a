// OSMesa: Mesa's off-screen software context. It offers desktop GL 4.5 core only (no GLES
// profile), which still compiles our `#version 300 es` shaders through ARB_ES3_compatibility.
// Chosen with PENUMBRA_GL=osmesa or --gl osmesa, and the last native fallback.
// libOSMesa is opened on first use, not linked: it brings LLVM and about 50 MB of start-up
// to every process otherwise, including those that never make a context.
#include <dlfcn.h>

#include <GL/osmesa.h>

#include <string>
#include <vector>

#include "platform/backends.h"

namespace penumbra::platform {
namespace {

// The four OSMesa entry points Penumbra uses, from the library opened at run time.
struct OsMesaApi {
  decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
  decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
  decltype(&OSMesaDestroyContext) destroyContext = nullptr;
};

Result<const OsMesaApi*> osMesa() {
  static OsMesaApi api;
  static std::string failure;
  static const bool loaded = [] {
    void* lib = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    if (!lib) lib = dlopen("libOSMesa.so", RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
      const char* e = dlerror();
      failure = std::string("cannot open libOSMesa: ") + (e ? e : "not found");
      return false;
    }
    api.createContextAttribs = reinterpret_cast<decltype(api.createContextAttribs)>(
        dlsym(lib, "OSMesaCreateContextAttribs"));
    api.makeCurrent = reinterpret_cast<decltype(api.makeCurrent)>(dlsym(lib, "OSMesaMakeCurrent"));
    api.getProcAddress =
        reinterpret_cast<decltype(api.getProcAddress)>(dlsym(lib, "OSMesaGetProcAddress"));
    api.destroyContext =
        reinterpret_cast<decltype(api.destroyContext)>(dlsym(lib, "OSMesaDestroyContext"));
    if (!api.createContextAttribs || !api.makeCurrent || !api.getProcAddress ||
        !api.destroyContext) {
      failure = "libOSMesa lacks OSMesaCreateContextAttribs and friends";
      return false;
    }
    return true;
  }();
  if (!loaded) return makeError(failure);
  return &api;
}

// OSMesaGetProcAddress through the opened library, in the loader's signature.
OSMESAproc osMesaGetProc(const char* name) {
  auto api = osMesa();
  return api ? (*api)->getProcAddress(name) : nullptr;
}

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext(const OsMesaApi& api, OSMesaContext ctx)
      : api_(api), ctx_(ctx), buffer_(4 * 4 * 4) {}
  ~OsMesaContext() override { api_.destroyContext(ctx_); }
  GlBackend backend() const override { return GlBackend::OSMesa; }
  std::string description() const override { return description_; }
  bool isDesktopGl() const override { return true; }
  Status makeCurrent() override {
    // OSMesa needs a colour buffer to be current; we render only into FBOs, so 4x4 is enough.
    if (!api_.makeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 4, 4)) {
      return makeError("OSMesaMakeCurrent failed");
    }
    if (!loadGlFunctions(reinterpret_cast<GetProcFn>(&osMesaGetProc))) {
      return makeError("could not load the GL entry points through OSMesa");
    }
    return {};
  }
  void setDescription(std::string d) { description_ = std::move(d); }

 private:
  const OsMesaApi& api_;
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
  auto api = osMesa();
  if (!api) return api.error();
  OSMesaContext ctx = (*api)->createContextAttribs(attribs, nullptr);
  if (!ctx) return makeError("OSMesaCreateContextAttribs (GL 3.3 core) failed");
  auto context = std::make_unique<OsMesaContext>(**api, ctx);
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
