// Cook-Torrance GGX microfacet BRDF with Smith height-correlated visibility and Schlick
// Fresnel (the glTF metallic-roughness model), and Lambert diffuse.
const float MIN_PERCEPTUAL_ROUGHNESS = 0.045;  // keeps alpha^2 representable in mediump too

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
  vec3 lr = normalize(centre + toRay * min(1.0, disk.w / max(length(toRay), 1e-6)));
  float widened = min(1.0, alpha + 0.5 * disk.w);
  float norm = (alpha / widened) * (alpha / widened);
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
  return D_GGX(NoH, alpha) * norm * V_SmithGGXCorrelated(NoV, NoL, alpha) * F_Schlick(f0, f90, VoH);
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
