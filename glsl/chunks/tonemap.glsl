// Display transforms: exposure, then Khronos PBR Neutral (default), ACES fitted (Hill),
// Reinhard or none, then the sRGB transfer curve. The operators' codes are generated from the
// C++ enum (PN_TONEMAP_*, passes/limits.h commonDefines).

vec3 pbrNeutral(vec3 color) {
  const float startCompression = 0.8 - 0.04;
  const float desaturation = 0.15;
  float x = min(color.r, min(color.g, color.b));
  float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  color -= offset;
  float peak = max(color.r, max(color.g, color.b));
  if (peak < startCompression) return color;
  const float d = 1.0 - startCompression;
  float newPeak = 1.0 - d * d / (peak + d - startCompression);
  color *= newPeak / peak;
  float g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
  return mix(color, vec3(newPeak), g);
}

vec3 acesFitted(vec3 color) {
  const mat3 inputMat = mat3(0.59719, 0.07600, 0.02840, 0.35458, 0.90834, 0.13383, 0.04823,
                             0.01566, 0.83777);
  const mat3 outputMat = mat3(1.60475, -0.10208, -0.00327, -0.53108, 1.10813, -0.07276,
                              -0.07367, -0.00605, 1.07602);
  color = inputMat * color;
  vec3 a = color * (color + 0.0245786) - 0.000090537;
  vec3 b = color * (0.983729 * color + 0.4329510) + 0.238081;
  return outputMat * (a / b);
}

vec3 toneMap(vec3 color, int op) {
  if (op == PN_TONEMAP_PBR_NEUTRAL) return pbrNeutral(color);
  if (op == PN_TONEMAP_ACES) return acesFitted(color);
  if (op == PN_TONEMAP_REINHARD) return color / (1.0 + color);
  return color;
}

vec3 linearToSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
