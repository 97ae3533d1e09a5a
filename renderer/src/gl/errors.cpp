#include "gl/errors.h"

#include <utility>

namespace penumbra::gl {

const char* errorName(GLenum error) {
  switch (error) {
    case GL_NO_ERROR:
      return "GL_NO_ERROR";
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case 0x0507:  // GL_CONTEXT_LOST (KHR_robustness, ES 3.2)
      return "GL_CONTEXT_LOST";
    case 0x9242:  // CONTEXT_LOST_WEBGL
      return "CONTEXT_LOST_WEBGL (the WebGL context was lost)";
    default:
      return "unknown GL error";
  }
}

const char* framebufferStatusName(GLenum status) {
  switch (status) {
    case GL_FRAMEBUFFER_COMPLETE:
      return "GL_FRAMEBUFFER_COMPLETE";
    case GL_FRAMEBUFFER_UNDEFINED:
      return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
      return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
      return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_UNSUPPORTED:
      return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
      return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
#ifdef GL_FRAMEBUFFER_INCOMPLETE_DIMENSIONS
    case GL_FRAMEBUFFER_INCOMPLETE_DIMENSIONS:
      return "GL_FRAMEBUFFER_INCOMPLETE_DIMENSIONS";
#endif
    default:
      return "unknown framebuffer status";
  }
}

namespace {

#ifdef __EMSCRIPTEN__
bool gDeferAllocationChecks = true;
#else
bool gDeferAllocationChecks = false;
#endif
// The first allocation since the last checkError() (deferred checks only).
std::string& pendingAllocation() {
  static std::string what;
  return what;
}

}  // namespace

Status checkError(const std::string& what) {
  std::string allocation;
  if (gDeferAllocationChecks) allocation = std::exchange(pendingAllocation(), {});
  GLenum first = GL_NO_ERROR;
  for (int i = 0; i < 16; ++i) {
    GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    if (first == GL_NO_ERROR) first = e;
  }
  if (first == GL_NO_ERROR) return {};
  const std::string where =
      allocation.empty() ? what : what + " (after " + allocation + ", or a later call)";
  if (first == GL_OUT_OF_MEMORY) {
    return makeError(where +
                     ": the GPU is out of memory (GL_OUT_OF_MEMORY); lower the resolution "
                     "or the shadow-map size");
  }
  return makeError(where + " failed: " + errorName(first));
}

void setDeferredAllocationChecks(bool deferred) {
  gDeferAllocationChecks = deferred;
  pendingAllocation().clear();
}

void beginAllocation() {
  if (!gDeferAllocationChecks) clearErrors();
}

Status checkAllocation(const std::string& what) {
  if (!gDeferAllocationChecks) return checkError(what);
  if (pendingAllocation().empty()) pendingAllocation() = what;
  return {};
}

void clearErrors() {
  for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; ++i) {
  }
}

}  // namespace penumbra::gl
