// MaterialFeatures: what a material uses that the shading programs are specialised on (a
// software rasterizer runs both sides of a branch even on a uniform, so a material's absent
// clearcoat, sheen or textures would otherwise cost every pixel). One table gives each feature
// its field, its #define and its width in bits; passes/lighting_variant.h packs it with the
// lighting switches into one program key and makes every #define from both tables.
#pragma once

#include <cstdint>

#include "penumbra/scene.h"

namespace penumbra {

// X(field, DEFINE, bits), read by chunks/material.glsl (programs without these defines, the
// prepass and the shadow maps', read the uniforms instead).
#define PN_MATERIAL_FEATURES(X)                                                                 \
  X(textures, PN_TEXTURES, 19)    /* bit i: TextureSlot i has a texture (or an array layer) */  \
  X(clearcoat, PN_CLEARCOAT, 1)   /* KHR_materials_clearcoat */                                 \
  X(sheen, PN_SHEEN, 1)           /* KHR_materials_sheen */                                     \
  X(unlit, PN_UNLIT, 1)           /* KHR_materials_unlit */                                     \
  X(alphaMode, PN_ALPHA_MODE, 2)  /* AlphaMode */                                               \
  X(broadLobe, PN_BROAD_LOBE, 1)  /* a dielectric's broad specular lobe, occluded as diffuse */ \
  X(lightCacheable, PN_LIGHT_CACHEABLE, 1) /* lobes broad enough for the lights' cache */       \
  X(iridescence, PN_IRIDESCENCE, 1)        /* KHR_materials_iridescence */                      \
  X(anisotropy, PN_ANISOTROPY, 1)          /* KHR_materials_anisotropy */                       \
  X(diffuseTransmission, PN_DIFFUSE_TRANSMISSION, 1) /* KHR_materials_diffuse_transmission */   \
  X(dispersion, PN_DISPERSION, 1)                    /* KHR_materials_dispersion */

static_assert(kTextureSlotCount == 19, "MaterialFeatures::textures has a bit a slot");

struct MaterialFeatures {
#define PN_FEATURE_FIELD(field, define, bits) uint32_t field = 0;
  PN_MATERIAL_FEATURES(PN_FEATURE_FIELD)
#undef PN_FEATURE_FIELD

  // The fields in the table's order, for grouping draws by program (not the program key).
  uint64_t order() const {
    uint64_t k = 0;
#define PN_FEATURE_ORDER(field, define, bits) k = (k << (bits)) | field;
    PN_MATERIAL_FEATURES(PN_FEATURE_ORDER)
#undef PN_FEATURE_ORDER
    return k;
  }
};

// Roughness from which a lobe counts as broad for the area lights' per-view cache.
inline constexpr float kLightCacheMinRoughness = 0.3f;
// A material's features, given which of its slots have a texture.
MaterialFeatures materialFeatures(const Material& m, const bool (&hasTexture)[kTextureSlotCount]);

}  // namespace penumbra
