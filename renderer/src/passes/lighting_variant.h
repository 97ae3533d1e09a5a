// LightingVariant: every switch a lighting.frag program is specialised on, in one table (after
// Filament's Variant). The table gives each switch its field, its #define and its width in
// bits; the struct makes both the program key and the #defines from it, so the two cannot
// disagree and a new switch is one line. The material's features (gpu/gpu_scene.h) complete
// the program's key.
#pragma once

#include <cstdint>
#include <string>

#include "gl/program.h"
#include "penumbra/error.h"

namespace penumbra::passes {

// X(field, DEFINE, bits): what glsl/lighting.frag's header lists.
#define PN_LIGHTING_SWITCHES(X)                                                                  \
  X(occlusion, PN_OCCLUSION, 1)               /* occlusion samples and screen-space indirect */  \
  X(area, PN_AREA, 1)                         /* area-light samples */                           \
  X(punctual, PN_PUNCTUAL, 1)                 /* punctual samples */                             \
  X(capture, PN_CAPTURE, 1)                   /* a probe's cube capture */                       \
  X(probeCacheWrite, PN_PROBE_CACHE_WRITE, 1) /* the probe volume's per-view cache */            \
  X(transmission, PN_TRANSMISSION, 2)    /* 1: a transmissive surface's own light, 2: compose */ \
  X(probes, PN_PROBES, 1)                /* the probe volume is on */                            \
  X(probeCache, PN_PROBE_CACHE, 1)       /* its per-view cache is read */                        \
  X(pointShadows, PN_POINT_SHADOWS, 1)   /* a punctual sample has a cube shadow map */           \
  X(punctualKinds, PN_PUNCTUAL_KINDS, 5) /* PunctualKindBits (passes/limits.h) */                \
  X(lightCache, PN_LIGHT_CACHE, 1)       /* area samples read the lights' cache */               \
  X(lightCacheWrite, PN_LIGHT_CACHE_WRITE, 3) /* lights written to that cache (0: none) */       \
  X(areaCount, PN_AREA_COUNT, 3)              /* the batch's area samples */                     \
  X(areaStarts, PN_AREA_STARTS, 4)            /* samples whose light is not the last one's */    \
  X(punctualCount, PN_PUNCTUAL_COUNT, 4)      /* the batch's punctual samples */                 \
  X(accumulate, PN_ACCUMULATE, 1)             /* the batch adds its sample to the mean */

struct LightingVariant {
#define PN_VARIANT_FIELD(field, define, bits) uint32_t field = 0;
  PN_LIGHTING_SWITCHES(PN_VARIANT_FIELD)
#undef PN_VARIANT_FIELD

  // The switches packed in the table's order (each checked to fit its bits).
  uint32_t key() const {
    uint32_t k = 0;
    int shift = 0;
#define PN_VARIANT_PACK(field, define, bits)                                             \
  PN_CHECK(field < (1u << (bits)), "LightingVariant: " #field " does not fit its bits"); \
  k |= field << shift;                                                                   \
  shift += (bits);
    PN_LIGHTING_SWITCHES(PN_VARIANT_PACK)
#undef PN_VARIANT_PACK
    return k;
  }

  gl::Defines defines() const {
    gl::Defines d;
#define PN_VARIANT_DEFINE(field, define, bits) d.emplace_back(#define, std::to_string(field));
    PN_LIGHTING_SWITCHES(PN_VARIANT_DEFINE)
#undef PN_VARIANT_DEFINE
    return d;
  }
};

#define PN_VARIANT_BITS(field, define, bits) +(bits)
static_assert(0 PN_LIGHTING_SWITCHES(PN_VARIANT_BITS) <= 32, "a lighting variant's key is 32 bits");
#undef PN_VARIANT_BITS

}  // namespace penumbra::passes
