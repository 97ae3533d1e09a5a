// Capabilities: what the current context can do for Penumbra (float colour buffers, float
// linear filtering, float blending, texture limits, timer queries), probed once, and the
// fallback policy that follows from it, e.g. RGBA16F accumulation where RGBA32F cannot be
// rendered to (many phones).
#pragma once

#include <string>
#include <vector>

#include "gl/texture.h"

namespace penumbra::gl {

struct Capabilities {
  std::string version;
  std::string renderer;
  bool desktopGl = false;
  bool colorBufferFloat = false;      // RGBA32F renderable
  bool colorBufferHalfFloat = false;  // RGBA16F renderable
  bool floatLinear = false;           // 32-bit float textures filterable
  bool floatBlend = false;            // blending into 32-bit float targets
  bool timerQuery = false;
  int maxTextureSize = 0;
  int maxCubeMapSize = 0;
  int maxDrawBuffers = 0;

  // Policy derived from the above.
  PixelFormat accumulationFormat = PixelFormat::RGBA8;
  std::vector<std::string> fallbacks;  // one line per fallback taken

  std::string report() const;
};

struct CapabilityOptions {
  bool forceHalfFloat = false;  // behave as if RGBA32F could not be rendered to
};

// Probes the current context. Float renderability is tested by building a small framebuffer
// rather than trusting extension strings (OSMesa reports none, but supports them in core).
Capabilities queryCapabilities(bool desktopGl, const CapabilityOptions& options = {});

}  // namespace penumbra::gl
