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
vec3 punctualSpecular(vec3 n, vec3 v, vec3 l, vec3 f0, float f90, float alpha, vec4 disk) {
  if (disk.w <= 0.0) return specularBrdf(n, v, l, f0, f90, alpha, 1.0) * max(dot(n, l), 0.0);
  vec3 centre = -disk.xyz;
  vec3 r = reflect(-v, n);
  vec3 toRay = dot(centre, r) * r - centre;
  vec3 lr = normalize(centre + toRay * min(1.0, disk.w / max(length(toRay), 1e-6)));
  float widened = min(1.0, alpha + 0.5 * disk.w);
  float norm = (alpha / widened) * (alpha / widened);
  return specularBrdf(n, v, lr, f0, f90, alpha, norm) * max(dot(n, lr), 0.0);
}

vec3 specularBrdf(vec3 n, vec3 v, vec3 l, vec3 f0, float f90, float alpha, float norm) {
  vec3 h = normalize(v + l);
  float NoV = max(dot(n, v), 1e-4);
  float NoL = max(dot(n, l), 0.0);
  float NoH = max(dot(n, h), 0.0);
  float VoH = max(dot(v, h), 0.0);
  return D_GGX(NoH, alpha) * norm * V_SmithGGXCorrelated(NoV, NoL, alpha) * F_Schlick(f0, f90, VoH);
}
