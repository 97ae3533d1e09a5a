// Loads the glad GLES 3.0 entry points (native builds). Kept apart from the EGL and OSMesa
// files because glad's header and the system GL headers cannot be included together.
#include <string>

#include "gl/gl.h"
#include "platform/backends.h"

namespace penumbra::platform {

int loadGlFunctions(GetProcFn getProc) {
  return gladLoadGLES2(reinterpret_cast<GLADloadfunc>(getProc));
}

std::string currentGlDescription() {
  auto str = [](GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return std::string(s ? s : "?");
  };
  return str(GL_VERSION) + " (" + str(GL_RENDERER) + ")";
}

void applyCommonState(bool desktopGl) {
  // ES 3.0 and WebGL2 always filter across cube faces; desktop GL must be told to.
  if (desktopGl) glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
}

}  // namespace penumbra::platform
