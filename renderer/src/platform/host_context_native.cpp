// GlContext::adoptCurrent and hardwareGpuPresent natively. adoptCurrent: the host's current
// context, entry points loaded through the host's loader (eglGetProcAddress by default). Nothing is
// created, made current or destroyed here, and no GL state is set: the Renderer saves and restores
// what it touches.
#include <EGL/egl.h>

#include <filesystem>

#include "platform/backends.h"

namespace penumbra {
namespace platform {
namespace {

class HostContext final : public GlContext {
 public:
  HostContext(std::string description, bool desktopGl)
      : description_(std::move(description)), desktopGl_(desktopGl) {}
  GlBackend backend() const override { return GlBackend::Host; }
  std::string description() const override { return description_; }
  Status makeCurrent() override { return {}; }  // the host's to manage
  bool isDesktopGl() const override { return desktopGl_; }

 private:
  std::string description_;
  bool desktopGl_;
};

}  // namespace

Result<std::unique_ptr<GlContext>> adoptHostContext(GetProcFn getProc, bool desktopGl) {
  if (!getProc) getProc = reinterpret_cast<GetProcFn>(&eglGetProcAddress);
  const int version = loadGlFunctions(getProc);
  if (!version) {
    return makeError("host context: cannot load the GL entry points (is a context current?)");
  }
  const std::string description = currentGlDescription();
  if (!desktopGl && version < 30000) {
    return makeError("host context: OpenGL ES 3.0 or later is needed, the current context has " +
                     description);
  }
  return std::unique_ptr<GlContext>(new HostContext("host context: " + description, desktopGl));
}

}  // namespace platform

bool GlContext::hardwareGpuPresent() {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/dev/dri", ec)) {
    if (entry.path().filename().string().rfind("renderD", 0) == 0) return true;
  }
  return std::filesystem::exists("/dev/nvidia0", ec) || std::filesystem::exists("/dev/dxg", ec);
}

Result<std::unique_ptr<GlContext>> GlContext::adoptCurrent(GetProcAddress getProcAddress,
                                                           bool desktopGl) {
  return platform::adoptHostContext(getProcAddress, desktopGl);
}

}  // namespace penumbra
