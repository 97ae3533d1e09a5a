// libFuzzer target: glTF / .glb loading from memory (JSON parsing, buffers, accessors, meshes,
// Draco, meshopt, materials, embedded images, lights, cameras, node graph).
// External URIs resolve against a folder that does not exist, so the fuzzer reads no files.
#include <cstddef>
#include <cstdint>
#include <span>

#include "penumbra/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  penumbra::LoadOptions options;
  options.memoryBudgetBytes = int64_t{256} << 20;  // keep RSS under libFuzzer's limit
  options.maxTextureSize = 1024;
  // The loader picks .glb or .gltf parsing by the name's extension: follow the magic, so both
  // the container and the JSON paths are fuzzed.
  const bool glb = size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
  auto scene = penumbra::loadGltfFromMemory(std::span<const uint8_t>(data, size),
                                            "/nonexistent-penumbra-fuzz",
                                            glb ? "fuzz.glb" : "fuzz.gltf", options);
  if (scene) {
    // Touch the result so the sanitizers see every element the loader claims to have made.
    size_t n = scene->triangleCount();
    (void)n;
    (void)penumbra::defaultCamera(*scene);
  }
  return 0;
}
