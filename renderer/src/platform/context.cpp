// Backend selection for GlContext::create: an explicit choice, PENUMBRA_GL, or the native
// fallback chain EGL surfaceless -> EGL device -> OSMesa.
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string>
#include <vector>

#include "platform/backends.h"

namespace penumbra {

const char* backendName(GlBackend backend) {
  switch (backend) {
    case GlBackend::Auto:
      return "auto";
    case GlBackend::EglSurfaceless:
      return "egl";
    case GlBackend::EglDevice:
      return "egl-device";
    case GlBackend::OSMesa:
      return "osmesa";
    case GlBackend::WebGL2:
      return "webgl2";
    case GlBackend::Host:
      return "host";
  }
  return "unknown";
}

Result<GlBackend> parseBackend(std::string_view name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (GlBackend b : {GlBackend::Auto, GlBackend::EglSurfaceless, GlBackend::EglDevice,
                      GlBackend::OSMesa, GlBackend::WebGL2}) {
    if (lower == backendName(b)) return b;
  }
  if (lower == "egl-surfaceless" || lower == "surfaceless") return GlBackend::EglSurfaceless;
  return makeError("unknown GL backend '" + std::string(name) +
                   "' (expected auto, egl, egl-device, osmesa or webgl2)");
}

namespace {

Result<std::unique_ptr<GlContext>> createOne(GlBackend backend, const ContextOptions& options) {
  switch (backend) {
    case GlBackend::EglSurfaceless:
      return platform::createEglContext(false);
    case GlBackend::EglDevice:
      return platform::createEglContext(true);
    case GlBackend::OSMesa:
      return platform::createOsMesaContext();
    case GlBackend::WebGL2:
      return platform::createWebGlContext(options);
    case GlBackend::Host:
      return makeError("the host backend wraps an existing context: use GlContext::adoptCurrent");
    case GlBackend::Auto:
      break;
  }
  return makeError("no backend chosen");
}

}  // namespace

Result<std::unique_ptr<GlContext>> GlContext::create(const ContextOptions& options) {
  GlBackend requested = options.backend;
  if (requested == GlBackend::Auto) {
    if (const char* env = std::getenv("PENUMBRA_GL"); env && *env) {
      auto parsed = parseBackend(env);
      if (!parsed) return makeError("PENUMBRA_GL: " + parsed.message());
      requested = *parsed;
    }
  }
  std::vector<GlBackend> chain;
  if (requested != GlBackend::Auto) {
    chain = {requested};
  } else {
#ifdef __EMSCRIPTEN__
    chain = {GlBackend::WebGL2};
#else
    chain = {GlBackend::EglSurfaceless, GlBackend::EglDevice, GlBackend::OSMesa};
#endif
  }
  std::string failures;
  for (GlBackend b : chain) {
    auto ctx = createOne(b, options);
    if (ctx) return ctx;
    if (!failures.empty()) failures += "; ";
    failures += std::string(backendName(b)) + ": " + ctx.message();
  }
  return makeError("no OpenGL ES 3.0 context could be created (tried " + failures + ")");
}

}  // namespace penumbra
