// ConvergenceState, one part of Renderer::Impl (render/renderer_impl.h): how an automatic view
// measures its convergence (render/convergence.cpp). The passes that compare the displayed
// image's tiles with a kept checkpoint and snapshot it, the frames the kept checkpoints hold,
// and the tile mask of the tiles no longer shaded.
#pragma once

#include <array>
#include <optional>

#include "passes/fullscreen_pass.h"
#include "progressive/convergence.h"

namespace penumbra {

struct ConvergenceState {
  std::optional<passes::FullscreenPass> convergence;         // made on an automatic view's first use
  std::optional<passes::FullscreenPass> checkpointSnapshot;  // likewise
  // The checkpoint whose displayed image each of targets->checkpoints holds (0: none this view).
  std::array<int, progressive::kKeptCheckpoints> checkpointFrames{};
  std::optional<passes::FullscreenPass> tileMaskPass;  // made on first use
  // The frame's stencil marks tiles this view no longer shades (skipTiles): the image units
  // (lighting, compose, accumulation) test it. Cleared by frame 1.
  bool tilesSkipped = false;
};

}  // namespace penumbra
