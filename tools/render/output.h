// penumbra-render's outputs: the displayed image (.png) or the linear radiance before exposure
// and tone mapping (.exr, .hdr), shared by the single render and the batch.
#pragma once

#include <string>

#include "penumbra/error.h"
#include "penumbra/renderer.h"

namespace penumbra::tools {

bool hasExtension(const std::string& path, const char* ext);
Status writeOutput(const std::string& path, Renderer& renderer);

}  // namespace penumbra::tools
