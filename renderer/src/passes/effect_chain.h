// EffectChain: what turns the accumulated mean (linear radiance) into the displayed image, in
// the order of passes/effects/registry.cpp. An effect reads the radiance so far and writes its
// own into a target of the image's size; the last member, tone mapping (always on), writes the
// chain's output: the display target (Renderer::toneMap) or a host's framebuffer (present).
// With no other effect enabled the chain is tone mapping alone, reading the mean itself. The
// linear read-back (readRadiance, EXR output) stays the mean: effects are for the eye.
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

// Where a member draws: one of the chain's RGBA16F targets of the image's size (linear
// filtering), or for the last member the chain's output, of any size.
struct EffectOutput {
  GLuint framebuffer = 0;  // a GL name: the chain's own target's, the display's or a host's
  int x = 0, y = 0, width = 0, height = 0;
  // Binds the framebuffer and sets the viewport.
  void bind() const;
};

class Effect {
 public:
  virtual ~Effect() = default;
  virtual const char* name() const = 0;
  virtual bool enabled(const RenderSettings& settings) const = 0;
  // Draws the effect of `in` into `out`.
  virtual Status apply(gl::ShaderLibrary& library, const EffectInput& in,
                       const EffectOutput& out) = 0;
};

// An RGBA16F target with linear filtering, as effects draw into (`what` names it in errors).
Result<ColorTarget> makeEffectTarget(int width, int height, const char* what);

using EffectFactory = std::unique_ptr<Effect> (*)();
// The effects in the order they run (passes/effects/registry.cpp), tone mapping last.
std::span<const EffectFactory> registeredEffects();

class EffectChain {
 public:
  // Runs the enabled effects on `mean` (the image's size) and the last member into `output`.
  // `halfFloat`: RGBA16F is renderable (the effects before the last need it; without, only
  // tone mapping runs).
  Status draw(gl::ShaderLibrary& library, const gl::Texture2D& mean, int width, int height,
              const RenderSettings& settings, bool halfFloat, const EffectOutput& output);

 private:
  std::vector<std::unique_ptr<Effect>> effects_;  // made on first use
  std::array<ColorTarget, 2> targets_;            // ping-pong, made on first use
  int width_ = 0, height_ = 0;
  Status ensureTargets(int width, int height);
};

}  // namespace penumbra::passes
