// Which light carries a scene at first sight: the paper's frame 1 is environment light only,
// which is right where the environment lights the scene and black where its own lights do.
// environmentShare estimates, before anything is drawn, the environment's part of the
// irradiance a surface of the scene receives; below one half the renderer asks the distributor
// for first light (distributeSamples: every light from its centre in frame 1). GL-free.
#pragma once

#include <vector>

#include "penumbra/scene.h"

namespace penumbra::progressive {

// The environment's share in [0, 1] of the irradiance at a typical point of a scene with these
// bounds: pi times its mean radiance (an open sky), against each light's irradiance at the
// distance of the bounds' radius or of the light from their centre, whichever is larger
// (area lights: L A / r^2, at most pi L; point and spot: I / r^2; directional: E). Channels
// by their largest. 1 without lights; 0 with a black environment and any light.
float environmentShare(const std::vector<Light>& lights, float environmentMeanRadiance,
                       const Bounds& bounds);

}  // namespace penumbra::progressive
