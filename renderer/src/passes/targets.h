// RenderTargets: the framebuffers of the progressive pipeline at one resolution — the
// intermediate frame (float colour + depth), the ping-pong accumulation pair, the depth and
// normal prepass, and the 8-bit display image.
#pragma once

#include <array>
#include <utility>

#include "gl/objects.h"
#include "gl/texture.h"
#include "progressive/convergence.h"

namespace penumbra::passes {

struct ColorTarget {
  gl::Texture2D color;
  gl::Framebuffer framebuffer;
};

struct RenderTargets {
  int width = 0;
  int height = 0;
  gl::PixelFormat format = gl::PixelFormat::RGBA32F;
  gl::PixelFormat prepassFormat = gl::PixelFormat::RGBA32F;  // also the probe cache's
  ColorTarget frame;  // this intermediate frame's radiance, with depth
  // Depth and stencil: the stencil marks the tiles an automatic view no longer shades.
  gl::Renderbuffer frameDepth;
  std::array<ColorTarget, 2> accumulation;
  int current = 0;      // accumulation[current] holds the running mean
  ColorTarget prepass;  // view normal + linear depth
  gl::Renderbuffer prepassDepth;
  ColorTarget display;  // RGBA8, display-encoded
  // The probe volume's per-view cache of its lookups (LightingPass), three layers of one array
  // (prepassFormat: RGBA16F where renderable), drawn at once: irradiance with a depth key, the
  // room's radiance, and the four probes' weights (which the occlusion rays' control variate
  // reuses). One texture unit for all. With the frame's depth, so only the pixels the frame
  // shades are written. Made on first use.
  gl::Texture2DArray probeCache;
  gl::Framebuffer probeCacheFramebuffer;
  gl::Texture2DArray lightCache;
  gl::Framebuffer lightCacheFramebuffer;

  // This frame's diffuse occlusion rays (OcclusionPass), a ray per block of block x block
  // pixels: ceil(width / block) x ceil(height / block), prepassFormat. Made on first use.
  ColorTarget occlusion;
  ColorTarget occlusionFiltered;  // the early frames' ray filter's first (row) pass
  int occlusionBlock = 0;
  int occlusionWidth(int block) const { return (width + block - 1) / block; }
  int occlusionHeight(int block) const { return (height + block - 1) / block; }

  // Transmissive surfaces (LightingPass): their own light, with the frame's depth, and the
  // copy of the frame they look through. Accumulation format; made on first use.
  ColorTarget glassLight;
  ColorTarget behind;

  // Stochastic transparency's early frames (progressive/first_frame_hold.h): frame 1's mean as
  // it was, and the displayed mix of it with the running mean. Accumulation format; made on
  // first use (views with BLEND surfaces only).
  ColorTarget firstFrame;
  ColorTarget held;

  // An automatic view's convergence measure (progressive/convergence.h): the displayed image
  // (tone-mapped, sRGB) of the last checkpoints, RGB10_A2 (a quarter of an 8-bit step, the
  // memory of one float copy of the mean for all four), and the tiles' changes, a texel a tile
  // of `tile` pixels in the accumulation format. Made on first use.
  std::array<ColorTarget, progressive::kKeptCheckpoints> checkpoints;
  ColorTarget convergenceTiles;
  gl::Texture2D tileMask;  // RGBA8, a texel a tile: red 255 where the tile is no longer shaded
  int tilesWidth(int tile) const { return (width + tile - 1) / tile; }
  int tilesHeight(int tile) const { return (height + tile - 1) / tile; }

  static Result<RenderTargets> create(int width, int height, gl::PixelFormat accumulationFormat,
                                      gl::PixelFormat prepassFormat);
  // After frame 1 the mean is frame 1 itself: the frame target becomes the mean by swapping
  // it with the other accumulation target (no accumulation pass), which becomes the frame
  // target. Every one of the three has the frame's depth attached, so any can be drawn into.
  Status ensureProbeCache();
  // The per-view cache of `layers` area lights' unshadowed shading (lighting_pass.h): a layer
  // a light, all drawn at once over the frame's depth. Remade when the count changes.
  Status ensureLightCache(int layers);
  Status ensureTransmission();
  Status ensureFirstFrameHold();
  Status ensureOcclusion(int block);
  Status ensureConvergence(int tile);

  void takeFrameAsMean() {
    std::swap(frame, accumulation[static_cast<size_t>(1 - current)]);
    current = 1 - current;
  }
};

}  // namespace penumbra::passes
