// glTF metallic-roughness material inputs: factors, the texture slots (each with its UV set
// and KHR_texture_transform matrix; penumbra/scene.h TextureSlot), vertex colour, alpha modes,
// normal mapping, and the KHR_materials_* extensions' factors times their textures.
#include "chunks/coverage.glsl"
// Programs specialised per material (the lighting programs'; gpu/material_features.h) know
// which textures and layers it has: a software rasterizer runs both sides of a branch even on
// a uniform, so what a material lacks would cost every pixel. The others (-1) read uniforms.
#ifndef PN_TEXTURES
#define PN_TEXTURES -1
#define PN_CLEARCOAT -1
#define PN_SHEEN -1
#define PN_UNLIT -1
#define PN_ALPHA_MODE -1
#define PN_BROAD_LOBE 0
#endif
// The later extensions' switches (lighting.frag's programs always define them).
#ifndef PN_IRIDESCENCE
#define PN_IRIDESCENCE 0
#endif
#ifndef PN_ANISOTROPY
#define PN_ANISOTROPY 0
#endif
#ifndef PN_DIFFUSE_TRANSMISSION
#define PN_DIFFUSE_TRANSMISSION 0
#endif
#ifndef PN_DISPERSION
#define PN_DISPERSION 0
#endif
uniform vec4 uBaseColorFactor;
uniform float uMetallicFactor;
uniform float uRoughnessFactor;
uniform vec3 uEmissive;  // emissiveFactor * emissive_strength
uniform float uNormalScale;
uniform float uOcclusionStrength;
uniform int uAlphaMode;  // 0 opaque, 1 mask, 2 blend
uniform float uAlphaCutoff;
// KHR_materials_ior and KHR_materials_specular: the dielectric reflectance at normal and at
// grazing incidence (0.04 and 1 by default); KHR_materials_unlit.
uniform vec3 uDielectricF0;
uniform float uDielectricF90;
uniform int uUnlit;
#ifndef PN_TEXTURE_SLOTS
#error "PN_TEXTURE_SLOTS (passes/limits.h) is not defined"
#endif
uniform int uTextureMask;  // bit i: slot i has a texture
// Per slot, the two rows of its KHR_texture_transform; w: its UV set (S), its layer in
// uMaterialLayers (T).
uniform vec4 uSlotUvS[PN_TEXTURE_SLOTS];
uniform vec4 uSlotUvT[PN_TEXTURE_SLOTS];
uniform sampler2D uBaseColorTex;
uniform sampler2D uMetallicRoughnessTex;
uniform sampler2D uNormalTex;
uniform sampler2D uOcclusionTex;
uniform sampler2D uEmissiveTex;
// The extension slots' textures, a layer each: one texture unit for all of them
// (gpu/gpu_scene.h). Colour layers hold sRGB bytes.
uniform highp sampler2DArray uMaterialLayers;
uniform float uClearcoatNormalScale;

const int SLOT_BASE = 0;
const int SLOT_MR = 1;
const int SLOT_NORMAL = 2;
const int SLOT_OCCLUSION = 3;
const int SLOT_EMISSIVE = 4;
const int SLOT_COAT_NORMAL = 5;
const int SLOT_COAT = 6;
const int SLOT_COAT_ROUGHNESS = 7;
const int SLOT_SHEEN_COLOR = 8;
const int SLOT_SHEEN_ROUGHNESS = 9;
const int SLOT_SPECULAR = 10;
const int SLOT_SPECULAR_COLOR = 11;
const int SLOT_TRANSMISSION = 12;
const int SLOT_THICKNESS = 13;
const int SLOT_IRIDESCENCE = 14;
const int SLOT_IRIDESCENCE_THICKNESS = 15;
const int SLOT_ANISOTROPY = 16;
const int SLOT_DIFFUSE_TRANSMISSION = 17;
const int SLOT_DIFFUSE_TRANSMISSION_COLOR = 18;

in vec3 vWorldPos;
in vec3 vNormal;
in vec4 vTangent;
in vec2 vUv0;
in vec2 vUv1;
in vec4 vColor;

struct SurfaceInputs {
  vec4 baseColor;
  float metallic;
  float perceptualRoughness;
  vec3 emissive;
  float occlusion;
  vec3 normal;  // world, facing the viewer for double-sided materials
};

bool hasTexture(int slot) {
  return PN_TEXTURES < 0 ? (uTextureMask & (1 << slot)) != 0 : (PN_TEXTURES & (1 << slot)) != 0;
}

vec2 slotUv(int slot) {
  vec3 uv = vec3(uSlotUvS[slot].w > 0.5 ? vUv1 : vUv0, 1.0);
  return vec2(dot(uSlotUvS[slot].xyz, uv), dot(uSlotUvT[slot].xyz, uv));
}

// An extension slot's texel.
vec4 layerTexel(int slot) {
  return texture(uMaterialLayers, vec3(slotUv(slot), uSlotUvT[slot].w));
}

vec3 srgbToLinear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}

vec4 baseColor() {
  vec4 c = uBaseColorFactor * vColor;
  if (hasTexture(SLOT_BASE)) c *= texture(uBaseColorTex, slotUv(SLOT_BASE));
  return c;
}

// MASK cuts out below the cutoff; BLEND keeps the fragment with probability alpha (when
// stochastic coverage is on). The same test runs in every pass that draws the surface.
void alphaTest(float alpha) {
#if PN_ALPHA_MODE < 0 || PN_ALPHA_MODE == 1
  if (uAlphaMode == 1 && alpha < uAlphaCutoff) discard;
#endif
#if PN_ALPHA_MODE < 0 || PN_ALPHA_MODE == 2
  if (uAlphaMode == 2 && !coverageKept(alpha)) discard;
#endif
}

// The interpolated normal, flipped on the back faces of double-sided materials.
vec3 geometricNormal() {
  vec3 n = normalize(vNormal);
  return gl_FrontFacing ? n : -n;
}

// A tangent-space normal map's texel `tn` (in [-1, 1]) applied to n (which geometricNormal()
// gave).
vec3 mappedNormal(vec3 n, vec3 tn, float scale) {
  if (dot(vTangent.xyz, vTangent.xyz) <= 1e-10) return n;
  bool flip = !gl_FrontFacing;
  // Back faces negate the whole tangent frame (as the Khronos sample viewer does).
  vec3 t = normalize(vTangent.xyz - n * dot(n, vTangent.xyz));
  if (flip) t = -t;
  vec3 b = cross(n, t) * (vTangent.w < 0.0 ? -1.0 : 1.0);
  if (flip) b = -b;
  tn.xy *= scale;
  return normalize(mat3(t, b, n) * tn);
}

SurfaceInputs readSurface(vec3 viewDir) {
  SurfaceInputs s;
  s.baseColor = baseColor();
  alphaTest(s.baseColor.a);
  if (PN_ALPHA_MODE == 0 || uAlphaMode == 0) s.baseColor.a = 1.0;
  s.metallic = uMetallicFactor;
  s.perceptualRoughness = uRoughnessFactor;
  if (hasTexture(SLOT_MR)) {
    vec4 mr = texture(uMetallicRoughnessTex, slotUv(SLOT_MR));
    s.perceptualRoughness *= mr.g;
    s.metallic *= mr.b;
  }
  s.metallic = saturate(s.metallic);
  s.perceptualRoughness = clamp(s.perceptualRoughness, MIN_PERCEPTUAL_ROUGHNESS, 1.0);
  s.emissive = uEmissive;
  if (hasTexture(SLOT_EMISSIVE)) s.emissive *= texture(uEmissiveTex, slotUv(SLOT_EMISSIVE)).rgb;
  s.occlusion = 1.0;
  if (hasTexture(SLOT_OCCLUSION)) {
    s.occlusion = 1.0 + uOcclusionStrength *
                            (texture(uOcclusionTex, slotUv(SLOT_OCCLUSION)).r - 1.0);
  }
  s.normal = geometricNormal();
  if (hasTexture(SLOT_NORMAL)) {
    vec3 tn = texture(uNormalTex, slotUv(SLOT_NORMAL)).xyz * 2.0 - 1.0;
    s.normal = mappedNormal(s.normal, tn, uNormalScale);
  }
  return s;
}

#include "chunks/material_extensions.glsl"
