// Whether a scene's surfaces can see one another. When none can (one convex body, or one
// plane), no light bounces from a surface onto another and nothing hides the sky from any
// surface: the probe volume and the occlusion rays would compute exactly what the environment
// and the lights give without them, so the renderer skips both for such a scene.
#pragma once

#include "penumbra/scene.h"

namespace penumbra {

// Scenes with more vertices than this are not tested and count as seeing themselves (the test
// costs a vertex loop per triangle).
inline constexpr int kSelfVisibilityMaxVertices = 2048;

// False when every triangle has all of the scene's vertices on or behind its plane (on it, for
// a double-sided one): then no surface faces another. True otherwise, and for scenes over
// kSelfVisibilityMaxVertices.
bool surfacesSeeEachOther(const Scene& scene);

}  // namespace penumbra
