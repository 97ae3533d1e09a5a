// The post effects, in the order they run on the mean (passes/effect_chain.h). Registering an
// effect is one line in PN_EFFECTS: the name of its factory, defined in its file in
// passes/effects/. Tone mapping stays last: the chain's last member writes the output.
#include "passes/effect_chain.h"

#define PN_EFFECTS(X) \
  X(makeBloom)        \
  X(makeToneMap)      \
  /* end */

namespace penumbra::passes {
namespace effects {
#define PN_DECLARE_EFFECT(factory) std::unique_ptr<Effect> factory();
PN_EFFECTS(PN_DECLARE_EFFECT)
#undef PN_DECLARE_EFFECT
}  // namespace effects

std::span<const EffectFactory> registeredEffects() {
#define PN_LIST_EFFECT(factory) &effects::factory,
  static const EffectFactory kEffects[] = {PN_EFFECTS(PN_LIST_EFFECT)};
#undef PN_LIST_EFFECT
  return kEffects;
}

}  // namespace penumbra::passes
