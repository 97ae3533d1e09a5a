// Capture LODs: coarse stand-ins for dense meshes, drawn where their detail cannot show. The
// probe volume's captures are 16 texels a face, and each renders the whole scene six times: a
// 114k-triangle model cost 46 ms a capture, all of it geometry. The stand-in keeps the surface
// within a small share of the scene's diagonal (meshoptimizer's simplifier), so the probes'
// irradiance and visibility are unchanged in practice. Natively Debian's meshoptimizer; in the
// browser the simplifier its author publishes on npm (web/lib/decoders.mjs loads it for a glTF
// with a primitive of at least kCaptureLodMinTriangles).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/scene.h"

namespace penumbra {

// Primitives with fewer triangles are drawn whole: simplifying them would save little (the
// material grid's 25 spheres of 3968 triangles each do get stand-ins).
inline constexpr size_t kCaptureLodMinTriangles = 1024;
// The largest deviation of a stand-in from its mesh, as a share of the scene's bounding-box
// diagonal: under half a capture texel seen from a fifth of the probe spacing at the default
// density (16 texels over 90 degrees; the spacing is about a sixth of the diagonal).
inline constexpr float kCaptureLodErrorFraction = 1.0f / 512.0f;

// The stand-in's triangle list (indices into prim's vertices) for a primitive drawn at most
// `maxScale` times its object-space size, in a scene whose diagonal is `sceneDiagonal`. Empty
// when the primitive is small, has a non-finite vertex, the simplifier is not available, or it
// removes under a quarter of the triangles: then the primitive itself is drawn.
std::vector<uint32_t> captureLod(const Primitive& prim, float maxScale, float sceneDiagonal);

// Whether this build can simplify (natively always; in the browser once the simplifier is
// loaded).
bool hasSimplifier();

namespace backend {
// meshoptimizer's simplifier: at most `targetError` deviation relative to the mesh's extent
// (its largest side), down to `targetIndexCount` indices if that comes first.
std::vector<uint32_t> simplify(std::span<const uint32_t> indices,
                               std::span<const glm::vec3> positions, size_t targetIndexCount,
                               float targetError);
}  // namespace backend

}  // namespace penumbra
