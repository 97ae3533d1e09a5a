// Split-sum environment lighting: irradiance from 9 SH coefficients (pre-convolved with the
// clamped cosine on the CPU, so E(n) = sum c_i Y_i(n)), the GGX-prefiltered specular cube
// (perceptual roughness r lives at mip r * (mips - 1)) and the DFG lookup table
// (R = A, G = B, B = A + B = E_ss for multiple-scattering compensation; A = the sheen lobe's
// directional albedo).
uniform samplerCube uEnvSpecular;
uniform sampler2D uDfgLut;
uniform vec3 uShIrradiance[9];
uniform float uEnvMaxMip;
uniform float uEnvIntensity;
uniform mat3 uEnvRotation;  // world direction -> environment direction

vec3 envIrradiance(vec3 nWorld) {
  vec3 n = uEnvRotation * nWorld;
  vec3 e = uShIrradiance[0] * 0.282095;
  e += uShIrradiance[1] * (0.488603 * n.y);
  e += uShIrradiance[2] * (0.488603 * n.z);
  e += uShIrradiance[3] * (0.488603 * n.x);
  e += uShIrradiance[4] * (1.092548 * n.x * n.y);
  e += uShIrradiance[5] * (1.092548 * n.y * n.z);
  e += uShIrradiance[6] * (0.315392 * (3.0 * n.z * n.z - 1.0));
  e += uShIrradiance[7] * (1.092548 * n.x * n.z);
  e += uShIrradiance[8] * (0.546274 * (n.x * n.x - n.y * n.y));
  return max(e, vec3(0.0)) * uEnvIntensity;
}

vec3 envRadiance(vec3 dirWorld, float perceptualRoughness) {
  float lod = clamp(perceptualRoughness, 0.0, 1.0) * uEnvMaxMip;
  return textureLod(uEnvSpecular, uEnvRotation * dirWorld, lod).rgb * uEnvIntensity;
}

// (A, B, E_ss) for n.v and perceptual roughness.
vec3 dfg(float NoV, float perceptualRoughness) {
  return textureLod(uDfgLut, vec2(NoV, perceptualRoughness), 0.0).rgb;
}

// The sheen lobe's directional albedo for n.v and sheen roughness (the table's alpha).
float sheenAlbedo(float NoV, float sheenRoughness) {
  return textureLod(uDfgLut, vec2(NoV, sheenRoughness), 0.0).a;
}
