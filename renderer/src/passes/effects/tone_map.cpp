// Tone mapping: exposure, the tone mapper and sRGB encoding of the radiance so far into the
// chain's output (the display target, or a host's framebuffer). The chain's last member and
// always on: the one effect that writes to the output itself (passes/effect_chain.h).
#include <cmath>
#include <optional>

#include "passes/effect_chain.h"
#include "passes/fullscreen_pass.h"

namespace penumbra::passes::effects {
namespace {

class ToneMap final : public Effect {
 public:
  const char* name() const override { return "tone mapping"; }
  bool enabled(const RenderSettings&) const override { return true; }

  Status apply(gl::ShaderLibrary& library, const EffectInput& in,
               const EffectOutput& out) override {
    // An output larger than the image (a browser's render size below its canvas) interpolates
    // displayed colours: a program of its own (glsl/effects/tonemap.frag says why).
    const bool filtered = out.width > in.width || out.height > in.height;
    std::optional<FullscreenPass>& slot = passes_[filtered ? 1 : 0];
    if (!slot) {
      auto made =
          FullscreenPass::create(library, "effects/tonemap.frag", false,
                                 filtered ? gl::Defines{{"PN_FILTERED", "1"}} : gl::Defines{});
      if (!made) return made.error();
      slot.emplace(std::move(*made));
    }
    out.bind();
    const gl::Program& p = slot->begin();
    p.bind("uRadiance", *in.radiance);
    p.set("uExposureScale", std::exp2(in.settings->exposure));
    p.set("uToneMapper", static_cast<int>(in.settings->toneMapper));
    p.set("uTransparent", in.settings->transparentBackground ? 1.0f : 0.0f);
    slot->draw();
    // The mean read here is the target the next frame's fused lighting draws into: a browser's
    // GL took every such draw for a feedback loop while it stayed bound (20 % slower frames).
    p.release("uRadiance");
    return {};
  }

 private:
  std::optional<FullscreenPass> passes_[2];  // plain, filtered: made on first use
};

}  // namespace

std::unique_ptr<Effect> makeToneMap() {
  return std::make_unique<ToneMap>();
}

}  // namespace penumbra::passes::effects
