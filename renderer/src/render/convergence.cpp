// Renderer::Impl::measureTiles: an automatic view's convergence measure at a checkpoint
// (progressive/convergence.h). glsl/convergence.frag compares the displayed image of the
// running mean with that of the previous checkpoint's mean, a texel per tile; the small result
// is read back, and the mean is copied for the next checkpoint.
#include "gl/errors.h"
#include "render/renderer_impl.h"

namespace penumbra {

Result<std::vector<float>> Renderer::Impl::measureTiles(int frame) {
  constexpr int tile = progressive::kConvergenceTile;
  PN_TRY(targets->ensureConvergence(tile));
  if (!convergence) {
    auto pass = passes::FullscreenPass::create(library, "convergence.frag", false,
                                               {{"PN_TILE", std::to_string(tile)}});
    if (!pass) return pass.error();
    convergence.emplace(std::move(*pass));
  }
  auto& t = *targets;
  const auto& mean = t.accumulation[static_cast<size_t>(t.current)];
  std::vector<float> rms;
  if (checkpointFrame > 0 && checkpointFrame < frame) {
    const int tw = t.tilesWidth(tile), th = t.tilesHeight(tile);
    t.convergenceTiles.framebuffer.bind();
    gl::setViewport(0, 0, tw, th);
    const gl::Program& p = convergence->begin();
    mean.color.bind(0);
    t.checkpoint.color.bind(1);
    p.set("uCurrent", 0);
    p.set("uPrevious", 1);
    p.set("uExposureScale", std::exp2(settings.exposure));
    p.set("uToneMapper", static_cast<int>(settings.toneMapper));
    convergence->draw();
    gl::Texture2D::unbind(0);
    gl::Texture2D::unbind(1);
  }
  // Queued before the read-back below waits for the GPU.
  mean.framebuffer.blitColorTo(t.checkpoint.framebuffer, t.width, t.height);
  if (checkpointFrame > 0 && checkpointFrame < frame) {
    const int tw = t.tilesWidth(tile), th = t.tilesHeight(tile);
    const std::vector<float> texels = t.convergenceTiles.framebuffer.readRgbaFloat(0, 0, 0, tw, th);
    rms.reserve(static_cast<size_t>(tw) * th);
    for (size_t i = 0; i < texels.size(); i += 4) rms.push_back(texels[i]);
  }
  checkpointFrame = frame;
  PN_TRY(gl::checkError("measuring convergence at frame " + std::to_string(frame)));
  return rms;
}

}  // namespace penumbra
