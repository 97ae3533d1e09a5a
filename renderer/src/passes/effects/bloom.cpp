// Bloom: a share of the image's light spread by a wide blur (glare around emissive surfaces,
// the sun's highlights), as product viewers offer it. Off by default (RenderSettings::bloom 0).
// A chain of half-size levels down to about 8 pixels (at most kMaxLevels), each a blur of the
// one above, summed back up with tent filters and mixed into the radiance with weight `bloom`:
// energy-conserving, so the image's mean is kept (glsl/effects/bloom.frag).
#include <algorithm>
#include <optional>

#include "passes/effect_chain.h"
#include "passes/fullscreen_pass.h"

namespace penumbra::passes::effects {
namespace {

constexpr int kMaxLevels = 6;
constexpr int kSmallestSide = 8;

class Bloom final : public Effect {
 public:
  const char* name() const override { return "bloom"; }
  bool enabled(const RenderSettings& settings) const override { return settings.bloom > 0.0f; }

  Status apply(gl::ShaderLibrary& library, const EffectInput& in,
               const EffectOutput& out) override {
    PN_TRY(ensure(library, in.width, in.height));
    const int n = static_cast<int>(levels_.size());
    // Down: the radiance into level 0, then each level into the next.
    draw(0, levels_[0], *in.radiance, nullptr, false);
    for (int i = 1; i < n; ++i) draw(1, levels_[static_cast<size_t>(i)], levels_[i - 1].color);
    // Up: each level's tent added to the one above (level i then holds levels i..n-1).
    for (int i = n - 1; i > 0; --i) {
      draw(2, levels_[static_cast<size_t>(i - 1)], levels_[static_cast<size_t>(i)].color, nullptr,
           true);
    }
    // Composite at full size.
    out.bind();
    const gl::Program& p = stages_[3]->begin();
    p.bind("uSource", *in.radiance);
    p.bind("uBloom", levels_[0].color);
    p.set("uStrength", std::clamp(in.settings->bloom, 0.0f, 1.0f));
    p.set("uLevels", static_cast<float>(n));
    stages_[3]->draw();
    p.release("uSource");
    p.release("uBloom");
    return {};
  }

 private:
  std::array<std::optional<FullscreenPass>, 4> stages_;
  std::vector<ColorTarget> levels_;
  int width_ = 0, height_ = 0;

  Status ensure(gl::ShaderLibrary& library, int width, int height) {
    for (int s = 0; s < 4; ++s) {
      if (stages_[static_cast<size_t>(s)]) continue;
      auto pass = FullscreenPass::create(library, "effects/bloom.frag", false,
                                         {{"PN_BLOOM_STAGE", std::to_string(s)}});
      if (!pass) return pass.error();
      stages_[static_cast<size_t>(s)].emplace(std::move(*pass));
    }
    if (!levels_.empty() && width_ == width && height_ == height) return {};
    levels_.clear();
    int w = width, h = height;
    while (static_cast<int>(levels_.size()) < kMaxLevels &&
           (levels_.empty() || std::min(w, h) / 2 >= kSmallestSide)) {
      w = std::max(1, (w + 1) / 2);
      h = std::max(1, (h + 1) / 2);
      auto t = makeEffectTarget(w, h, "bloom level");
      if (!t) return t.error();
      levels_.push_back(std::move(*t));
    }
    width_ = width;
    height_ = height;
    return {};
  }

  // One stage into `target`, reading `source` (and `bloom`); `add`: blended onto the target.
  void draw(int stage, const ColorTarget& target, const gl::Texture2D& source,
            const gl::Texture2D* bloom = nullptr, bool add = false) {
    target.framebuffer.bind();
    gl::setViewport(0, 0, target.color.width(), target.color.height());
    const gl::Program& p = stages_[static_cast<size_t>(stage)]->begin();
    if (add) {
      gl::apply({.depthTest = gl::DepthTest::Off,
                 .depthWrite = false,
                 .blend = gl::Blend::Additive,
                 .cull = gl::Cull::None});
    }
    p.bind("uSource", source);
    p.set("uTexel", glm::vec2(1.0f / static_cast<float>(source.width()),
                              1.0f / static_cast<float>(source.height())));
    if (bloom) p.bind("uBloom", *bloom);
    stages_[static_cast<size_t>(stage)]->draw();
    p.release("uSource");
  }
};

}  // namespace

std::unique_ptr<Effect> makeBloom() {
  return std::make_unique<Bloom>();
}

}  // namespace penumbra::passes::effects
