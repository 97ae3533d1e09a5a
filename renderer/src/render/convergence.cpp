// Renderer::Impl::measureTiles: an automatic view's convergence measure at a checkpoint
// (progressive/convergence.h). glsl/convergence.frag compares the displayed image of the
// running mean with a kept checkpoint's, a texel per tile; the small result is read back, and
// the displayed image is kept (checkpoint_snapshot.frag) in place of the oldest. skipTiles:
// adaptive frames, the tiles measured converged marked in the frame's stencil
// (glsl/tile_mask.frag).
#include <algorithm>

#include "gl/errors.h"
#include "render/renderer_impl.h"

namespace penumbra {

Result<progressive::TileChanges> Renderer::Impl::measureTiles(int frame) {
  constexpr int tile = progressive::kConvergenceTile;
  PN_TRY(targets->ensureConvergence(tile));
  for (auto [pass, file] : {std::pair{&convergence, "convergence.frag"},
                            std::pair{&checkpointSnapshot, "checkpoint_snapshot.frag"}}) {
    if (*pass) continue;
    auto made =
        passes::FullscreenPass::create(library, file, false, {{"PN_TILE", std::to_string(tile)}});
    if (!made) return made.error();
    pass->emplace(std::move(*made));
  }
  auto& t = *targets;
  const auto& mean = t.accumulation[static_cast<size_t>(t.current)];
  const auto displayUniforms = [&](const gl::Program& p) {
    p.bind("uCurrent", mean.color);
    p.set("uExposureScale", std::exp2(settings.exposure));
    p.set("uToneMapper", static_cast<int>(settings.toneMapper));
  };
  progressive::TileChanges changes;
  changes.against = progressive::comparisonCheckpoint(frame, checkpointFrames);
  const auto kept = [&](int f) {
    return static_cast<size_t>(std::find(checkpointFrames.begin(), checkpointFrames.end(), f) -
                               checkpointFrames.begin());
  };
  const int tw = t.tilesWidth(tile), th = t.tilesHeight(tile);
  if (changes.against > 0) {
    t.convergenceTiles.framebuffer.bind();
    gl::setViewport(0, 0, tw, th);
    const gl::Program& p = convergence->begin();
    displayUniforms(p);
    p.bind("uPrevious", t.checkpoints[kept(changes.against)].color);
    convergence->draw();
    p.release("uPrevious");
    p.release("uCurrent");
  }
  // This checkpoint's displayed image replaces the oldest kept (an empty slot is 0). Queued
  // before the read-back below waits for the GPU.
  const size_t slot = kept(*std::min_element(checkpointFrames.begin(), checkpointFrames.end()));
  t.checkpoints[slot].framebuffer.bind();
  gl::setViewport(0, 0, t.width, t.height);
  const gl::Program& snapshot = checkpointSnapshot->begin();
  displayUniforms(snapshot);
  checkpointSnapshot->draw();
  snapshot.release("uCurrent");
  checkpointFrames[slot] = frame;
  if (changes.against > 0) {
    const std::vector<float> texels = t.convergenceTiles.framebuffer.readRgbaFloat(0, 0, 0, tw, th);
    changes.rms.reserve(static_cast<size_t>(tw) * th);
    changes.max.reserve(static_cast<size_t>(tw) * th);
    for (size_t i = 0; i < texels.size(); i += 4) {
      changes.rms.push_back(texels[i]);
      changes.max.push_back(texels[i + 2]);
    }
  }
  PN_TRY(gl::checkError("measuring convergence at frame " + std::to_string(frame)));
  return changes;
}

Status Renderer::Impl::skipTiles(std::span<const uint8_t> mask) {
  constexpr int tile = progressive::kConvergenceTile;
  auto& t = *targets;
  const int tw = t.tilesWidth(tile), th = t.tilesHeight(tile);
  PN_CHECK(mask.size() == static_cast<size_t>(tw) * static_cast<size_t>(th),
           "skipTiles: a mask byte per tile of the targets");
  PN_TRY(t.ensureConvergence(tile));
  if (!tileMaskPass) {
    auto pass = passes::FullscreenPass::create(library, "tile_mask.frag", false,
                                               {{"PN_TILE", std::to_string(tile)}});
    if (!pass) return pass.error();
    tileMaskPass.emplace(std::move(*pass));
  }
  std::vector<uint8_t> texels(mask.size() * 4, 0);
  for (size_t i = 0; i < mask.size(); ++i) texels[i * 4] = mask[i] ? 255 : 0;
  t.tileMask.upload(0, texels.data(), gl::DataType::UInt8);
  // The mask is the union of every checkpoint's: redrawn whole into a cleared stencil.
  const auto& mean = t.accumulation[static_cast<size_t>(t.current)];
  mean.framebuffer.bind();
  gl::setViewport(0, 0, t.width, t.height);
  gl::clearStencil();
  const gl::Program& p = tileMaskPass->begin();
  gl::apply({.depthTest = gl::DepthTest::Off,
             .depthWrite = false,
             .cull = gl::Cull::None,
             .colorWrite = false});
  gl::setStencil(gl::StencilMode::Mark);
  p.bind("uMask", t.tileMask);
  tileMaskPass->draw();
  gl::setStencil(gl::StencilMode::Off);
  p.release("uMask");
  gl::apply({});
  // Both accumulation targets hold the skipped tiles' mean from now on, so the ping-pong,
  // which no longer writes them, reads the same mean from either.
  mean.framebuffer.blitColorTo(t.accumulation[static_cast<size_t>(1 - t.current)].framebuffer,
                               t.width, t.height);
  tilesSkipped = true;
  PN_TRY(gl::checkError("marking converged tiles"));
  return {};
}

}  // namespace penumbra
