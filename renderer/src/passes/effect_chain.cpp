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

void EffectOutput::bind() const {
  gl::Framebuffer::bindExternal(framebuffer);
  gl::setViewport(x, y, width, height);
}

Status EffectChain::draw(gl::ShaderLibrary& library, const gl::Texture2D& mean, int width,
                         int height, const RenderSettings& settings, bool halfFloat,
                         const EffectOutput& output) {
  if (effects_.empty()) {
    for (EffectFactory make : registeredEffects()) effects_.push_back(make());
  }
  const gl::Texture2D* radiance = &mean;
  size_t next = 0;
  for (size_t i = 0; i < effects_.size(); ++i) {
    Effect& effect = *effects_[i];
    const bool last = i + 1 == effects_.size();
    PN_CHECK(!last || effect.enabled(settings), "the chain's last member is always on");
    // (documented: the effects before the last need RGBA16F targets)
    if (!last && (!halfFloat || !effect.enabled(settings))) continue;
    if (!last) PN_TRY(ensureTargets(width, height));
    const ColorTarget* target = last ? nullptr : &targets_[next];
    const EffectOutput out =
        last ? output : EffectOutput{target->framebuffer.id(), 0, 0, width, height};
    PN_TRY(effect.apply(library, {radiance, width, height, &settings}, out));
    PN_TRY(gl::checkError(std::string("post effect ") + effect.name()));
    if (!last) {
      radiance = &target->color;
      next = 1 - next;
    }
  }
  return {};
}

}  // namespace penumbra::passes
