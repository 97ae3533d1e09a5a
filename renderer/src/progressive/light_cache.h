// The per-view cache of the area lights' unshadowed shading (passes/lighting_pass.h): how many
// jittered frames of a still view it averages before the frames after them read it. Frame 1
// (what a viewer sees while the view moves) stays a plain forward pass; frames 2 to 1 + K each
// add 1 / K of their shading at their own sub-pixel position, so the cached mean is
// antialiased like the image.
#pragma once

#include <algorithm>

namespace penumbra::progressive {

// K for a view of m frames: a quarter of them, 4 to 32. Fewer positions lose small highlights
// (a mirror's reflection of a light, under a pixel: kitchen RMSE against Cycles +4.2 % with 8,
// +1.9 % with 16, +1.4 % with 32 at m = 128); more cost more frames than the cache saves.
inline int lightCacheFrames(int m) {
  return std::clamp(m / 4, 4, 32);
}

// Views shorter than this do without the cache: its build frames would be a large share of
// them, and in a browser each of its two programs' first use is a compile mid-convergence.
inline constexpr int kLightCacheMinFrames = 32;

// Whether frame `frame` of a view of m frames adds to the cache, given how many already have.
inline bool writesLightCache(int frame, int written, int m) {
  return m >= kLightCacheMinFrames && frame >= 2 && written < lightCacheFrames(m);
}
// Whether the cache is complete (its frames are all in).
inline bool lightCacheReady(int written, int m) {
  return m >= kLightCacheMinFrames && written >= lightCacheFrames(m);
}

}  // namespace penumbra::progressive
