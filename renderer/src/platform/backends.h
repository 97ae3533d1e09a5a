// Internal: the factory functions of each context backend, chosen by GlContext::create.
#pragma once

#include <memory>

#include "penumbra/gl_context.h"

namespace penumbra::platform {

// Loads the GLES 3.0 entry points through `getProc` into the process-wide loader. Returns the
// loaded version (major * 10000 + minor) or 0 on failure. Native only.
using GetProcFn = void (*(*)(const char*))();
int loadGlFunctions(GetProcFn getProc);
// Reads GL_VERSION and GL_RENDERER of the current context.
std::string currentGlDescription();
// One-time state that every backend needs after creation (e.g. seamless cube maps on desktop GL).
void applyCommonState(bool desktopGl);

Result<std::unique_ptr<GlContext>> createEglContext(bool devicePlatform);
Result<std::unique_ptr<GlContext>> createOsMesaContext();
Result<std::unique_ptr<GlContext>> createWebGlContext(const ContextOptions& options);
Result<std::unique_ptr<GlContext>> adoptHostContext(GetProcFn getProc, bool desktopGl);

}  // namespace penumbra::platform
