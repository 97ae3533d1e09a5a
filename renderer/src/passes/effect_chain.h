// EffectChain: the post effects between the accumulated mean (linear radiance) and tone
// mapping, in the order of passes/effects/registry.cpp. An effect reads the radiance so far and
// writes its own into a target of the image's size; tone mapping (the chain's last member,
// always on: Renderer's toneMap and present) maps the result to the display. With no effect
// enabled the chain costs nothing: tone mapping reads the mean itself. The linear read-back
// (readRadiance, EXR output) stays the mean: effects are for the eye.
// A new effect is one file in passes/effects/ (its class and its factory) with its shader in
// glsl/effects/, plus one line in the registry (docs/architecture.md, "A new post effect").
#pragma once

#include <array>
#include <memory>
#include <span>
#include <vector>

#include "gl/program.h"
#include "passes/targets.h"
#include "penumbra/settings.h"

namespace penumbra::passes {

struct EffectInput {
  const gl::Texture2D* radiance = nullptr;  // the radiance so far (the mean, or an effect's)
  int width = 0;
  int height = 0;
  const RenderSettings* settings = nullptr;
};

class Effect {
 public:
  virtual ~Effect() = default;
  virtual const char* name() const = 0;
  virtual bool enabled(const RenderSettings& settings) const = 0;
  // Draws the effect of `in` into `out` (RGBA16F, the image's size, linear filtering).
  virtual Status apply(gl::ShaderLibrary& library, const EffectInput& in,
                       const ColorTarget& out) = 0;
};

// An RGBA16F target with linear filtering, as effects draw into (`what` names it in errors).
Result<ColorTarget> makeEffectTarget(int width, int height, const char* what);

using EffectFactory = std::unique_ptr<Effect> (*)();
// The effects in the order they run (passes/effects/registry.cpp).
std::span<const EffectFactory> registeredEffects();

class EffectChain {
 public:
  // The radiance to tone map: `mean` itself when no effect is enabled, else the last enabled
  // effect's output. `halfFloat`: RGBA16F is renderable (effects need it; without, none runs).
  Result<const gl::Texture2D*> run(gl::ShaderLibrary& library, const gl::Texture2D& mean, int width,
                                   int height, const RenderSettings& settings, bool halfFloat);

 private:
  std::vector<std::unique_ptr<Effect>> effects_;  // made on first use
  std::array<ColorTarget, 2> targets_;            // ping-pong, made on first use
  int width_ = 0, height_ = 0;
  Status ensureTargets(int width, int height);
};

}  // namespace penumbra::passes
