#include "passes/targets.h"

#include <string>

namespace penumbra::passes {
namespace {

Result<ColorTarget> makeColor(int w, int h, gl::PixelFormat format, const gl::Renderbuffer* depth) {
  auto tex = gl::Texture2D::create(
      {.width = w,
       .height = h,
       .format = format,
       .sampler = {.minFilter = gl::Filter::Nearest, .magFilter = gl::Filter::Nearest}});
  if (!tex) return tex.error();
  ColorTarget t{std::move(*tex), gl::Framebuffer::create()};
  t.framebuffer.attachColor(0, t.color);
  if (depth) t.framebuffer.attachDepth(*depth);
  t.framebuffer.setDrawBuffers(1);
  PN_TRY(t.framebuffer.checkComplete());
  return t;
}

// A half-float array of `layers` layers and a framebuffer drawing all of them at once over
// `depth` (the per-view caches).
Status makeLayers(int w, int h, gl::PixelFormat format, int layers, const gl::Renderbuffer& depth,
                  const char* what, gl::Texture2DArray& texture, gl::Framebuffer& framebuffer) {
  auto array = gl::Texture2DArray::create(
      {.width = w,
       .height = h,
       .format = format,
       .sampler = {.minFilter = gl::Filter::Nearest, .magFilter = gl::Filter::Nearest}},
      layers);
  if (!array) return makeError(std::string(what) + " target: " + array.message());
  gl::Framebuffer fb = gl::Framebuffer::create();
  for (int i = 0; i < layers; ++i) fb.attachColor(i, *array, i);
  fb.attachDepth(depth);
  fb.setDrawBuffers(layers);
  PN_TRY(fb.checkComplete());
  texture = std::move(*array);
  framebuffer = std::move(fb);
  return {};
}

}  // namespace

Result<RenderTargets> RenderTargets::create(int w, int h, gl::PixelFormat format,
                                            gl::PixelFormat prepassFormat) {
  RenderTargets t;
  t.width = w;
  t.height = h;
  t.format = format;
  t.prepassFormat = prepassFormat;
  // With stencil: an automatic view marks the tiles it no longer shades (adaptive frames).
  auto fd = gl::Renderbuffer::create(w, h, gl::PixelFormat::Depth24Stencil8);
  if (!fd) return fd.error();
  t.frameDepth = std::move(*fd);
  auto pd = gl::Renderbuffer::create(w, h, gl::PixelFormat::Depth24);
  if (!pd) return pd.error();
  t.prepassDepth = std::move(*pd);
  auto frame = makeColor(w, h, format, &t.frameDepth);
  if (!frame) return makeError("frame target: " + frame.message());
  t.frame = std::move(*frame);
  for (auto& a : t.accumulation) {
    // With the frame's depth too: frame 1 is not accumulated but swapped in (takeFrameAsMean),
    // and the former accumulation target then serves as the next frame's target.
    auto acc = makeColor(w, h, format, &t.frameDepth);
    if (!acc) return makeError("accumulation target: " + acc.message());
    a = std::move(*acc);
  }
  auto pre = makeColor(w, h, prepassFormat, &t.prepassDepth);
  if (!pre) return makeError("prepass target: " + pre.message());
  t.prepass = std::move(*pre);
  auto disp = makeColor(w, h, gl::PixelFormat::RGBA8, nullptr);
  if (!disp) return makeError("display target: " + disp.message());
  t.display = std::move(*disp);
  gl::Framebuffer::bindDefault();
  return t;
}

Status RenderTargets::ensureProbeCache() {
  if (probeCache) return {};
  return makeLayers(width, height, prepassFormat, 3, frameDepth, "probe cache", probeCache,
                    probeCacheFramebuffer);
}

Status RenderTargets::ensureLightCache(int layers) {
  if (lightCache && lightCache.layers() == layers) return {};
  return makeLayers(width, height, prepassFormat, layers, frameDepth, "light cache", lightCache,
                    lightCacheFramebuffer);
}

Status RenderTargets::ensureTransmission() {
  if (glassLight.color) return {};
  auto light = makeColor(width, height, format, &frameDepth);
  if (!light) return makeError("transmission target: " + light.message());
  auto copy = makeColor(width, height, format, nullptr);
  if (!copy) return makeError("transmission target: " + copy.message());
  glassLight = std::move(*light);
  behind = std::move(*copy);
  return {};
}

Status RenderTargets::ensureFirstFrameHold() {
  if (firstFrame.color) return {};
  auto first = makeColor(width, height, format, nullptr);
  if (!first) return makeError("first-frame target: " + first.message());
  auto mix = makeColor(width, height, format, nullptr);
  if (!mix) return makeError("first-frame target: " + mix.message());
  firstFrame = std::move(*first);
  held = std::move(*mix);
  return {};
}

Status RenderTargets::ensureOcclusion(int block) {
  if (occlusion.color && occlusionBlock == block) return {};
  auto t = makeColor(occlusionWidth(block), occlusionHeight(block), prepassFormat, nullptr);
  if (!t) return makeError("occlusion target: " + t.message());
  auto f = makeColor(occlusionWidth(block), occlusionHeight(block), prepassFormat, nullptr);
  if (!f) return makeError("occlusion target: " + f.message());
  occlusion = std::move(*t);
  occlusionFiltered = std::move(*f);
  occlusionBlock = block;
  return {};
}

Status RenderTargets::ensureConvergence(int tile) {
  if (convergenceTiles.color) return {};
  for (auto& c : checkpoints) {
    auto snap = makeColor(width, height, gl::PixelFormat::RGB10A2, nullptr);
    if (!snap) return makeError("checkpoint target: " + snap.message());
    c = std::move(*snap);
  }
  auto tiles = makeColor(tilesWidth(tile), tilesHeight(tile), format, nullptr);
  if (!tiles) return makeError("convergence target: " + tiles.message());
  auto mask = gl::Texture2D::create(
      {.width = tilesWidth(tile),
       .height = tilesHeight(tile),
       .format = gl::PixelFormat::RGBA8,
       .sampler = {.minFilter = gl::Filter::Nearest, .magFilter = gl::Filter::Nearest}});
  if (!mask) return makeError("tile mask: " + mask.message());
  convergenceTiles = std::move(*tiles);
  tileMask = std::move(*mask);
  return {};
}

}  // namespace penumbra::passes
