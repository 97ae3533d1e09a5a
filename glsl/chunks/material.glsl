// glTF metallic-roughness material inputs: factors, the five texture slots (each with its UV
// set and KHR_texture_transform matrix), vertex colour, alpha modes, normal mapping.
#include "chunks/coverage.glsl"
// Programs specialised per material (lighting.frag's; gpu/gpu_scene.h materialDefines) know
// which textures and layers it has: a software rasterizer runs both sides of a branch even on
// a uniform, so what a material lacks would cost every pixel. The others (-1) read uniforms.
#ifndef PN_MATERIAL_KEYED
#define PN_TEXTURES -1
#define PN_CLEARCOAT -1
#define PN_SHEEN -1
#define PN_UNLIT -1
#define PN_ALPHA_MODE -1
#define PN_BROAD_LOBE 0
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
// KHR_materials_clearcoat (factors): layer strength and perceptual roughness.
uniform float uClearcoat;
uniform float uClearcoatRoughness;
// KHR_materials_sheen (factors): colour (0 = no sheen) and perceptual roughness.
uniform vec3 uSheenColor;
uniform float uSheenRoughness;
// KHR_materials_transmission and KHR_materials_volume (factors): the transmitted share of the
// dielectric base, the volume's thickness (mesh units; 0 thin-walled), its index of refraction
// and Beer-Lambert attenuation (distance 0: none).
uniform float uTransmission;
uniform float uThickness;
uniform float uIor;
uniform float uAttenuationDistance;
uniform vec3 uAttenuationColor;
uniform int uTextureMask;   // bit i: slot i has a texture
uniform int uTexCoordMask;  // bit i: slot i reads TEXCOORD_1
uniform mat3 uUvTransform[6];
uniform sampler2D uBaseColorTex;
uniform sampler2D uMetallicRoughnessTex;
uniform sampler2D uNormalTex;
uniform sampler2D uOcclusionTex;
uniform sampler2D uEmissiveTex;
uniform sampler2D uClearcoatNormalTex;  // KHR_materials_clearcoat's own normal map
uniform float uClearcoatNormalScale;

const int SLOT_BASE = 0;
const int SLOT_MR = 1;
const int SLOT_NORMAL = 2;
const int SLOT_OCCLUSION = 3;
const int SLOT_EMISSIVE = 4;
const int SLOT_COAT_NORMAL = 5;

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
  vec2 uv = (uTexCoordMask & (1 << slot)) != 0 ? vUv1 : vUv0;
  return (uUvTransform[slot] * vec3(uv, 1.0)).xy;
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

// A tangent-space normal map applied to n (which geometricNormal() gave).
vec3 mappedNormal(vec3 n, sampler2D map, int slot, float scale) {
  if (dot(vTangent.xyz, vTangent.xyz) <= 1e-10) return n;
  bool flip = !gl_FrontFacing;
  // Back faces negate the whole tangent frame (as the Khronos sample viewer does).
  vec3 t = normalize(vTangent.xyz - n * dot(n, vTangent.xyz));
  if (flip) t = -t;
  vec3 b = cross(n, t) * (vTangent.w < 0.0 ? -1.0 : 1.0);
  if (flip) b = -b;
  vec3 tn = texture(map, slotUv(slot)).xyz * 2.0 - 1.0;
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
  if (hasTexture(SLOT_NORMAL)) s.normal = mappedNormal(s.normal, uNormalTex, SLOT_NORMAL, uNormalScale);
  return s;
}

// The clearcoat's normal: its own normal map if it has one, else the geometric normal.
vec3 clearcoatNormal() {
  vec3 n = geometricNormal();
  return hasTexture(SLOT_COAT_NORMAL)
             ? mappedNormal(n, uClearcoatNormalTex, SLOT_COAT_NORMAL, uClearcoatNormalScale)
             : n;
}
