// The GPU path of the split-sum prefilter: the same PrefilteredEnvironment as
// ibl::prefilterCpu (same face order and orientation, same roughness per mip, SH from mip 0),
// computed with OpenGL ES 3.0 fragment shaders through a current GlContext. The CPU path is
// the reference; tests hold the two within a stated tolerance. On software rasterizers the
// CPU path is faster, so callers ask gpuPrefilterIsFaster() before choosing.
#pragma once

#include "penumbra/environment_format.h"
#include "penumbra/ibl.h"
#include "penumbra/image.h"

namespace penumbra {

// Needs a current GL context. `panorama` must be 2:1 and free of NaN/Inf/negative values.
Result<PackedEnvironment> prefilterGpu(const Image& panorama, const ibl::PrefilterOptions& options);

// False on software rasterizers (llvmpipe, softpipe, SwiftShader), where the multi-threaded
// CPU path wins; true on hardware. Needs a current GL context.
bool gpuPrefilterIsFaster();

}  // namespace penumbra
