#include "passes/effect_chain.h"

#include "gl/errors.h"

namespace penumbra::passes {

Result<ColorTarget> makeEffectTarget(int width, int height, const char* what) {
  auto tex = gl::Texture2D::create(
      {.width = width,
       .height = height,
       .format = gl::PixelFormat::RGBA16F,
       .sampler = {.minFilter = gl::Filter::Linear, .magFilter = gl::Filter::Linear}});
  if (!tex) return makeError(std::string(what) + ": " + tex.message());
  ColorTarget t{std::move(*tex), gl::Framebuffer::create()};
  t.framebuffer.attachColor(0, t.color);
  PN_TRY(t.framebuffer.checkComplete());
  return t;
}

Status EffectChain::ensureTargets(int width, int height) {
  if (targets_[0].color && width_ == width && height_ == height) return {};
  for (ColorTarget& t : targets_) {
    auto made = makeEffectTarget(width, height, "effect target");
    if (!made) return made.error();
    t = std::move(*made);
  }
  width_ = width;
  height_ = height;
  return {};
}

Result<const gl::Texture2D*> EffectChain::run(gl::ShaderLibrary& library, const gl::Texture2D& mean,
                                              int width, int height, const RenderSettings& settings,
                                              bool halfFloat) {
  if (effects_.empty()) {
    for (EffectFactory make : registeredEffects()) effects_.push_back(make());
  }
  const gl::Texture2D* radiance = &mean;
  if (!halfFloat) return radiance;  // (documented: effects need RGBA16F targets)
  size_t next = 0;
  for (auto& effect : effects_) {
    if (!effect->enabled(settings)) continue;
    PN_TRY(ensureTargets(width, height));
    const ColorTarget& out = targets_[next];
    PN_TRY(effect->apply(library, {radiance, width, height, &settings}, out));
    PN_TRY(gl::checkError(std::string("post effect ") + effect->name()));
    radiance = &out.color;
    next = 1 - next;
  }
  return radiance;
}

}  // namespace penumbra::passes
