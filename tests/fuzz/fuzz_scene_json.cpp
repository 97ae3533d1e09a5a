// libFuzzer target: Penumbra scene files (parseSceneJson) and the settings validation that
// every consumer runs on the result.
#include <cstddef>
#include <cstdint>
#include <string>

#include "penumbra/scene_file.h"
#include "penumbra/settings.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto file = penumbra::parseSceneJson(text, "/nonexistent-penumbra-fuzz", "fuzz.json");
  if (file) (void)penumbra::validate(file->settings);
  return 0;
}
