// LightingVariant: every switch a lighting program (glsl/lighting.frag and its siblings, one
// per output) is specialised on, in one table (after Filament's Variant): each switch's field,
// its #define and its width in bits. ProgramKey, with the material's features
// (gpu/material_features.h), makes both the program key and every #define from the two tables,
// so the two cannot disagree and a new switch is one line.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "gl/program.h"
#include "gpu/material_features.h"
#include "penumbra/error.h"
#include "scene/light_kinds.h"

namespace penumbra::passes {

// X(field, DEFINE, bits): what glsl/chunks/lighting_common.glsl's header lists.
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
  X(punctualKinds, PN_PUNCTUAL_KINDS, 5) /* a bit per PunctualSample (scene/light_kinds.h) */    \
  X(lightCache, PN_LIGHT_CACHE, 1)       /* area samples read the lights' cache */               \
  X(lightCacheWrite, PN_LIGHT_CACHE_WRITE, 3) /* lights written to that cache (0: none) */       \
  X(areaCount, PN_AREA_COUNT, 3)              /* the batch's area samples */                     \
  X(areaStarts, PN_AREA_STARTS, 4)            /* samples whose light is not the last one's */    \
  X(punctualCount, PN_PUNCTUAL_COUNT, 4)      /* the batch's punctual samples */                 \
  X(accumulate, PN_ACCUMULATE, 1)             /* the batch adds its sample to the mean */

static_assert(static_cast<int>(PunctualSample::Count) <= 5, "PN_PUNCTUAL_KINDS has 5 bits");

struct LightingVariant {
#define PN_VARIANT_FIELD(field, define, bits) uint32_t field = 0;
  PN_LIGHTING_SWITCHES(PN_VARIANT_FIELD)
#undef PN_VARIANT_FIELD

  // One program per output (glsl/chunks/lighting_common.glsl): the fragment shader's file.
  const char* fragmentFile() const {
    if (capture) return "probe_capture.frag";
    if (probeCacheWrite) return "probe_cache.frag";
    if (lightCacheWrite) return "light_cache.frag";
    if (transmission == 2) return "transmission_compose.frag";
    return "lighting.frag";
  }
};

// The program key: one table (PN_PROGRAM_KEY: the lighting switches, then the material's
// features) gives both the key and every #define of a lighting program. Fields are packed in
// the table's order into two 64-bit words, none straddling them.
#define PN_PROGRAM_KEY(X) PN_LIGHTING_SWITCHES(X) PN_MATERIAL_FEATURES(X)

namespace program_key_detail {
#define PN_KEY_WIDTH(field, define, bits) (bits),
inline constexpr int kWidths[] = {PN_PROGRAM_KEY(PN_KEY_WIDTH)};
#undef PN_KEY_WIDTH
// The bits the packing leaves free (at the end of each word).
constexpr int freeBits() {
  int word = 0, shift = 0;
  for (const int bits : kWidths) {
    if (shift + bits > 64) ++word, shift = 0;
    shift += bits;
  }
  return (64 - shift) + (word == 0 ? 64 : 0);
}
}  // namespace program_key_detail

// What docs/architecture.md states: room for at least 16 more switches' bits.
inline constexpr int kProgramKeyFreeBits = program_key_detail::freeBits();
static_assert(kProgramKeyFreeBits >= 16, "the program key needs 16 free bits");

struct ProgramKey : LightingVariant, MaterialFeatures {
  ProgramKey() = default;
  ProgramKey(const LightingVariant& v, const MaterialFeatures& f)
      : LightingVariant(v), MaterialFeatures(f) {}

  std::array<uint64_t, 2> key() const {
    std::array<uint64_t, 2> k{};
    size_t word = 0;
    int shift = 0;
#define PN_KEY_PACK(field, define, bits)                                            \
  PN_CHECK(field < (1ull << (bits)), "ProgramKey: " #field " does not fit its bits"); \
  if (shift + (bits) > 64) ++word, shift = 0;                                       \
  k[word] |= static_cast<uint64_t>(field) << shift;                                 \
  shift += (bits);
    PN_PROGRAM_KEY(PN_KEY_PACK)
#undef PN_KEY_PACK
    return k;
  }

  gl::Defines defines() const {
    gl::Defines d;
#define PN_KEY_DEFINE(field, define, bits) d.emplace_back(#define, std::to_string(field));
    PN_PROGRAM_KEY(PN_KEY_DEFINE)
#undef PN_KEY_DEFINE
    return d;
  }
};

}  // namespace penumbra::passes
