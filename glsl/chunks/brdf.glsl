// Cook-Torrance GGX microfacet BRDF with Smith height-correlated visibility and Schlick
// Fresnel (the glTF metallic-roughness model), and Lambert diffuse.
const float MIN_PERCEPTUAL_ROUGHNESS = 0.045;  // keeps alpha^2 representable in mediump too

#ifndef PN_ANISOTROPY
#define PN_ANISOTROPY 0
#endif
#if PN_ANISOTROPY
// KHR_materials_anisotropy: the base lobe's frame (the direction t, b = n x t), roughnesses
// along t and b, and the bent normal its environment reflection uses, set once per pixel by
// surfaceLayers (chunks/layers.glsl). specularBrdf() evaluates the anisotropic lobe while
// gAnisotropic is set: the clearcoat's evaluations clear it around themselves.
vec3 gAnisoT, gAnisoB, gBentNormal;
float gAlphaT, gAlphaB;
bool gAnisotropic = false;

// Anisotropic GGX and its height-correlated Smith visibility (Heitz 2014; alpha_t along t).
float D_GGXAnisotropic(float NoH, float ToH, float BoH, float at, float ab) {
  float a2 = at * ab;
  vec3 f = vec3(ab * ToH, at * BoH, a2 * NoH);
  float w2 = a2 / max(dot(f, f), 1e-12);
  return a2 * w2 * w2 / PI;
}

float V_SmithGGXCorrelatedAnisotropic(float NoV, float NoL, float ToV, float BoV, float ToL,
                                      float BoL, float at, float ab) {
  float ggxV = NoL * length(vec3(at * ToV, ab * BoV, NoV));
  float ggxL = NoV * length(vec3(at * ToL, ab * BoL, NoL));
  return 0.5 / max(ggxV + ggxL, 1e-7);
}
#endif

// The reflection direction the prefiltered environment is read along: bent toward the
// anisotropy's stretch where the material has one. (Lights' representative points keep the
// mirror direction: with the bent one, the brushed sphere of assets/extensions was 0.27 RMSE
// from Cycles around its highlight instead of 0.19.)
vec3 specularReflection(vec3 v, vec3 n) {
#if PN_ANISOTROPY
  if (gAnisotropic) return reflect(-v, gBentNormal);
#endif
  return reflect(-v, n);
}

float D_GGX(float NoH, float alpha) {
  float a2 = alpha * alpha;
  float f = (NoH * a2 - NoH) * NoH + 1.0;
  return a2 / (PI * f * f + 1e-12);
}

// Height-correlated Smith visibility V = G / (4 NoL NoV) (Heitz 2014).
float V_SmithGGXCorrelated(float NoV, float NoL, float alpha) {
  float a2 = alpha * alpha;
  float ggxV = NoL * sqrt(NoV * NoV * (1.0 - a2) + a2);
  float ggxL = NoV * sqrt(NoL * NoL * (1.0 - a2) + a2);
  return 0.5 / max(ggxV + ggxL, 1e-7);
}

vec3 F_Schlick(vec3 f0, float VoH) {
  float f = pow(1.0 - VoH, 5.0);
  return f0 + (vec3(1.0) - f0) * f;
}

// With a grazing reflectance f90 below 1 (KHR_materials_specular's weight on dielectrics).
vec3 F_Schlick(vec3 f0, float f90, float VoH) {
  float f = pow(1.0 - VoH, 5.0);
  return f0 + (vec3(f90) - f0) * f;
}

// Specular BRDF value (no cosine) for light direction l; `norm` scales D for area lights
// (Karis' energy normalisation of the widened lobe).
vec3 specularBrdf(vec3 n, vec3 v, vec3 l, vec3 f0, float f90, float alpha, float norm);

// Specular reflected by a punctual light of unit irradiance at normal incidence arriving
// along l: f_s(l) (n.l). disk.w > 0 makes it a disk at infinity (the sun, directional lights:
// disk.xyz its centre's direction of travel, disk.w tan(angular radius)), shaded with Karis'
// representative point, the direction within the disk closest to the reflection ray, and the
// lobe widened and renormalised as for area lights: the jittered sample direction l only
// places the shadow, and its point highlight would converge to a scatter of dots on smooth
// surfaces, not to the disk.
vec3 diskSpecular(vec3 n, vec3 v, vec3 f0, float f90, float alpha, vec4 disk) {
  vec3 centre = -disk.xyz;
  vec3 r = reflect(-v, n);
  vec3 toRay = dot(centre, r) * r - centre;
  vec3 offset = toRay * min(1.0, disk.w / max(length(toRay), 1e-6));
#if PN_ANISOTROPY
  // A lobe narrow across the stretch (alpha_b) sees the disk only where the ray's offset across
  // it lies within the disk: the point keeps that offset and moves along the stretch as far as
  // the disk allows. The radial point dropped the offset wherever the ray passed the disk far
  // along the stretch, so a smooth anisotropic metal's streak was a line alpha_b wide instead of
  // the disk's width, and dimmed by the renormalisation below (AnisotropyStrengthTest).
  if (gAnisotropic) {
    vec3 across = gAnisoB - dot(gAnisoB, centre) * centre;
    float len = length(across);
    if (len > 1e-4) {
      across /= len;
      vec3 along = cross(centre, across);
      float y = clamp(dot(toRay, across), -disk.w, disk.w);
      float chord = sqrt(max(disk.w * disk.w - y * y, 0.0));
      vec3 stretched = clamp(dot(toRay, along), -chord, chord) * along + y * across;
      offset = mix(offset, stretched, 1.0 - gAlphaB / gAlphaT);
    }
  }
#endif
  vec3 lr = normalize(centre + offset);
  float widened = min(1.0, alpha + 0.5 * disk.w);
  float norm = (alpha / widened) * (alpha / widened);
#if PN_ANISOTROPY
  // An anisotropic lobe is widened along each of its axes: GGX's peak scales as
  // 1 / (alpha_t alpha_b), so the renormalisation is the product of the two ratios (the
  // isotropic alpha's square took most of a mirror's streak away: AnisotropyStrengthTest).
  if (gAnisotropic) {
    norm = (gAlphaT / min(1.0, gAlphaT + 0.5 * disk.w)) * (gAlphaB / min(1.0, gAlphaB + 0.5 * disk.w));
  }
#endif
  return specularBrdf(n, v, lr, f0, f90, alpha, norm) * max(dot(n, lr), 0.0);
}

vec3 punctualSpecular(vec3 n, vec3 v, vec3 l, vec3 f0, float f90, float alpha, vec4 disk) {
  if (disk.w <= 0.0) return specularBrdf(n, v, l, f0, f90, alpha, 1.0) * max(dot(n, l), 0.0);
  return diskSpecular(n, v, f0, f90, alpha, disk);
}

vec3 specularBrdf(vec3 n, vec3 v, vec3 l, vec3 f0, float f90, float alpha, float norm) {
  vec3 h = normalize(v + l);
  float NoV = max(dot(n, v), 1e-4);
  float NoL = max(dot(n, l), 0.0);
  float NoH = max(dot(n, h), 0.0);
  float VoH = max(dot(v, h), 0.0);
#if PN_ANISOTROPY
  if (gAnisotropic) {
    return D_GGXAnisotropic(NoH, dot(gAnisoT, h), dot(gAnisoB, h), gAlphaT, gAlphaB) * norm *
           V_SmithGGXCorrelatedAnisotropic(NoV, NoL, dot(gAnisoT, v), dot(gAnisoB, v),
                                           dot(gAnisoT, l), dot(gAnisoB, l), gAlphaT, gAlphaB) *
           F_Schlick(f0, f90, VoH);
  }
#endif
  return D_GGX(NoH, alpha) * norm * V_SmithGGXCorrelated(NoV, NoL, alpha) * F_Schlick(f0, f90, VoH);
}

// KHR_materials_iridescence: the reflectance of a thin film (index filmIor, `thickness`
// nanometres) over a base of normal reflectance baseF0, seen from air at cosTheta1. Belcour and
// Barla's Airy summation (SIGGRAPH 2017): the film's two interfaces (Schlick), the phase shifts
// at each, and the first two interference orders integrated against the CIE 1931 matching
// functions, which their Gaussian fit makes a closed form (its constants below), then XYZ to
// linear sRGB. The film's index fades to air's over its first nanometres, so a film of
// thickness 0 leaves the base's Fresnel.
const mat3 XYZ_TO_LINEAR_SRGB = mat3(3.2404542, -0.9692660, 0.0556434, -1.5371385, 1.8760108,
                                     -0.2040259, -0.4985314, 0.0415560, 1.0572252);

vec3 filmSensitivity(float opd, vec3 shift) {
  float phase = 2.0 * PI * opd * 1e-9;
  const vec3 val = vec3(5.4856e-13, 4.4201e-13, 5.2481e-13);
  const vec3 pos = vec3(1.6810e+06, 1.7953e+06, 2.2084e+06);
  const vec3 var = vec3(4.3278e+09, 9.3046e+09, 6.6121e+09);
  vec3 xyz = val * sqrt(2.0 * PI * var) * cos(pos * phase + shift) * exp(-phase * phase * var);
  xyz.x += 9.7470e-14 * sqrt(2.0 * PI * 4.5282e+09) * cos(2.2399e+06 * phase + shift.x) *
           exp(-4.5282e+09 * phase * phase);
  return XYZ_TO_LINEAR_SRGB * (xyz / 1.0685e-7);
}

vec3 thinFilmFresnel(float filmIor, float cosTheta1, float thickness, vec3 baseF0) {
  float eta2 = mix(1.0, filmIor, smoothstep(0.0, 3.0, thickness));
  float sin2Sq = (1.0 - cosTheta1 * cosTheta1) / (eta2 * eta2);
  if (sin2Sq >= 1.0) return vec3(1.0);  // total internal reflection into the film
  float cosTheta2 = sqrt(1.0 - sin2Sq);
  // Air -> film.
  float r0 = (eta2 - 1.0) / (eta2 + 1.0);
  float R12 = F_Schlick(vec3(r0 * r0), cosTheta1).x;
  float T121 = 1.0 - R12;
  float phi21 = eta2 < 1.0 ? 0.0 : PI;  // the reflection inside the film toward air
  // Film -> base, the base's index from its reflectance (seen from air).
  vec3 s = sqrt(clamp(baseF0, vec3(0.0), vec3(0.9999)));
  vec3 baseIor = (1.0 + s) / (1.0 - s);
  vec3 r1 = (baseIor - eta2) / (baseIor + eta2);
  vec3 R23 = F_Schlick(r1 * r1, cosTheta2);
  vec3 phi23 = PI * (vec3(1.0) - step(vec3(eta2), baseIor));  // pi where the base is lower
  float opd = 2.0 * eta2 * thickness * cosTheta2;
  vec3 phi = vec3(phi21) + phi23;
  // (No lower bound: without a first interface, R12 = 0, there is no film to interfere.)
  vec3 R123 = min(R12 * R23, vec3(0.9999));
  vec3 Rs = T121 * T121 * R23 / (vec3(1.0) - R123);
  vec3 I = R12 + Rs;
  vec3 Cm = Rs - T121;
  for (int m = 1; m <= 2; ++m) {
    Cm *= sqrt(R123);
    I += Cm * 2.0 * filmSensitivity(float(m) * opd, float(m) * phi);
  }
  return clamp(I, vec3(0.0), vec3(1.0));  // the fit leaves a little out of gamut
}

// KHR_materials_sheen: Charlie's distribution with Estevez & Kulla's visibility, the same
// functions as ibl/sheen.cpp (which tabulates the lobe's directional albedo into the DFG
// table's alpha).
float sheenAlpha(float perceptualRoughness) {
  float r = clamp(perceptualRoughness, 0.07, 1.0);
  return r * r;
}

float sheenD(float NoH, float alpha) {
  float sin2 = max(1.0 - NoH * NoH, 0.0);
  float inv = 1.0 / alpha;
  return (2.0 + inv) * pow(sin2, 0.5 * inv) / (2.0 * PI);
}

float sheenLambdaFit(float x, float alpha) {
  float t = (1.0 - alpha) * (1.0 - alpha);
  float a = mix(21.5473, 25.3245, t);
  float b = mix(3.82987, 3.32435, t);
  float c = mix(0.19823, 0.16801, t);
  float d = mix(-1.97760, -1.27393, t);
  float e = mix(-4.32054, -4.85967, t);
  return a / (1.0 + b * pow(x, c)) + d * x + e;
}

float sheenLambda(float cosTheta, float alpha) {
  return cosTheta < 0.5 ? exp(sheenLambdaFit(cosTheta, alpha))
                        : exp(2.0 * sheenLambdaFit(0.5, alpha) - sheenLambdaFit(1.0 - cosTheta, alpha));
}

float sheenV(float NoV, float NoL, float alpha) {
  NoV = max(NoV, 1e-4);
  NoL = max(NoL, 1e-4);
  return saturate(1.0 / ((1.0 + sheenLambda(NoV, alpha) + sheenLambda(NoL, alpha)) * 4.0 * NoV * NoL));
}

// The sheen lobe's D V (n.l) for light from l (0 below the horizon).
float sheenBrdfCos(vec3 n, vec3 v, vec3 l, float alpha) {
  float NoL = dot(n, l);
  if (NoL <= 0.0) return 0.0;
  float NoH = dot(n, normalize(v + l));
  return sheenD(NoH, alpha) * sheenV(dot(n, v), NoL, alpha) * NoL;
}
