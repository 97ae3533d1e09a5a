// GlContext::adoptCurrent in the browser: not offered (the web viewer module owns its WebGL2
// context); a page embeds Penumbra through web/lib/penumbra.mjs instead.
#include "platform/backends.h"

namespace penumbra {

bool GlContext::hardwareGpuPresent() {
  return true;
}

Result<std::unique_ptr<GlContext>> GlContext::adoptCurrent(GetProcAddress, bool) {
  return makeError("GlContext::adoptCurrent is native only; in a page use web/lib/penumbra.mjs");
}

}  // namespace penumbra
