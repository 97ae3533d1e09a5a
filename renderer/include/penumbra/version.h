// The library version, printed by every tool's --version and written into generated files.
#pragma once

namespace penumbra {
const char* version();
}
