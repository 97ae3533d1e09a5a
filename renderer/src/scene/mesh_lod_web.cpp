// mesh_lod.h's simplifier in the browser: meshoptimizer's npm simplifier, which
// web/lib/decoders.mjs loads (as Module.penumbraDecoders.simplifier) for a glTF with a primitive
// large enough to need it. Without it, or if it throws, the meshes are drawn whole: no JS
// exception crosses into the wasm code.
#include <emscripten/emscripten.h>

#include "scene/mesh_lod.h"

// clang-format off
EM_JS(int, pn_simplifier_loaded, (), {
  const d = Module["penumbraDecoders"];
  return d && d["simplifier"] ? 1 : 0;
});

// Writes the simplified list over `out` (room for `count` indices); returns its length, 0 when
// the simplifier fails.
EM_JS(double, pn_simplify, (const uint32_t* indices, double count, const float* positions,
                            double vertices, double target, double error, uint32_t* out), {
  try {
    const s = Module["penumbraDecoders"]["simplifier"];
    const index = HEAPU32.slice(indices >>> 2, (indices >>> 2) + count);
    const pos = HEAPF32.slice(positions >>> 2, (positions >>> 2) + vertices * 3);
    const result = s.simplify(index, pos, 3, target, error, [])[0];
    if (result.length > count) return 0;
    HEAPU32.set(result, out >>> 2);
    return result.length;
  } catch (e) {
    console.warn(`[penumbra] mesh simplifier: ${e && e.message ? e.message : e}`);
    return 0;
  }
});
// clang-format on

namespace penumbra {

bool hasSimplifier() {
  return pn_simplifier_loaded() != 0;
}

namespace backend {

std::vector<uint32_t> simplify(std::span<const uint32_t> indices,
                               std::span<const glm::vec3> positions, size_t targetIndexCount,
                               float targetError) {
  std::vector<uint32_t> out(indices.size());
  const double n = pn_simplify(indices.data(), static_cast<double>(indices.size()),
                               &positions.data()->x, static_cast<double>(positions.size()),
                               static_cast<double>(targetIndexCount), targetError, out.data());
  out.resize(static_cast<size_t>(n));
  return out;
}

}  // namespace backend
}  // namespace penumbra
