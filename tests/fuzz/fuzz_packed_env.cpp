// libFuzzer target: the packed environment format (RGBE image + PENUMBRA_ENV JSON manifest).
#include <cstddef>
#include <cstdint>
#include <span>

#include "penumbra/environment_format.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  auto env =
      penumbra::readPackedEnvironmentFromMemory(std::span<const uint8_t>(data, size), "fuzz.hdr");
  (void)env;
  return 0;
}
