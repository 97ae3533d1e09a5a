#include "penumbra/version.h"

namespace penumbra {
const char* version() {
  return PENUMBRA_VERSION;
}
}  // namespace penumbra
