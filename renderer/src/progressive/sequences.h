// Fixed, seeded sample sequences of the progressive renderer: sub-pixel jitter, the
// per-frame occlusion sequence, and stratified points on area lights ordered from the centre
// outward. Everything is a pure function of (index, count, seed), so frame n is reproducible.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace penumbra::progressive {

// Radical inverse of `index` in `base` (Halton component), in [0, 1).
float radicalInverse(uint32_t index, uint32_t base);
// The R2 sequence (Roberts 2018): the plastic-number Kronecker sequence, in [0, 1)^2.
glm::vec2 r2(uint32_t index);
// A seed-derived offset in [0, 1)^2 for Cranley-Patterson rotation (seed 0 = no rotation).
glm::vec2 seedOffset(uint32_t seed, uint32_t stream);

// Sub-pixel jitter of frame `frame` (1-based) in pixels, in [-0.5, 0.5]^2. Frame 1 is
// unjittered; later frames follow a Kronecker sequence rotated by the seed, which stays
// centred on the pixel on every k-th frame (the frames a light's samples land on).
glm::vec2 jitter(int frame, uint32_t seed);

enum class LightShape { Rect, Disk, Point };

// n stratified points (Hammersley, Cranley-Patterson rotated by the seed) in [0,1]^2, sorted
// by distance of their image on the light from its centre: Euclidean on a rect of the given
// aspect (width / height), radial (concentric mapping) on a disk.
std::vector<glm::vec2> lightSamplePoints(int n, LightShape shape, float aspect, uint32_t seed);

// Point `index` of a light's open-ended sequence in [0,1]^2 (R2, rotated by the seed): every
// prefix is stratified, so an automatic view that stops anywhere has sampled the light evenly.
// Index 0 is the centre for seed 0. A point light's is always its centre.
glm::vec2 lightSequencePoint(uint32_t index, LightShape shape, uint32_t seed);
// Sorts points by the distance of their image on the light from its centre (as
// lightSamplePoints orders its own).
void sortFromCentre(std::vector<glm::vec2>& pts, LightShape shape, float aspect);

// Shirley-Chiu concentric mapping of [0,1]^2 onto the unit disk (area-preserving, keeps
// stratification); the centre 0.5, 0.5 maps to the origin.
glm::vec2 concentricDisk(glm::vec2 u);

}  // namespace penumbra::progressive
