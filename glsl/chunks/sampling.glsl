// Sampling used by progressive occlusion; mirrors renderer/src/ibl/sampling.h, where each
// function sits next to its PDF and is tested.
uniform vec2 uSequence;  // this frame's point of the low-discrepancy sequence, in [0, 1)^2

// Interleaved gradient noise (Jimenez 2014): a cheap per-pixel offset with blue-ish spectrum.
float interleavedGradientNoise(vec2 pixel) {
  return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

// PCG-based 2D hash (Jarzynski & Olano 2020): uncorrelated values per pixel, no pattern.
uvec2 pcg2d(uvec2 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * 1664525u;
  v.y += v.x * 1664525u;
  v = v ^ (v >> 16u);
  v.x += v.y * 1664525u;
  v.y += v.x * 1664525u;
  v = v ^ (v >> 16u);
  return v;
}

vec2 hash2(vec2 pixel, uint stream) {
  uvec2 h = pcg2d(uvec2(pixel) + uvec2(stream * 7919u, stream * 104729u));
  return vec2(h >> 8u) * (1.0 / 16777216.0);
}

// The frame's sequence point, Cranley-Patterson rotated by a fixed per-pixel offset: each
// pixel walks the low-discrepancy sequence over the frames, and neighbouring pixels are
// decorrelated (a structured offset such as interleaved gradient noise leaves visible
// patterns in the converging image).
vec2 pixelSample(vec2 pixel, float stream) {
  return fract(uSequence + hash2(pixel, uint(stream) + 1u));
}

// Cosine-weighted hemisphere direction around +Z; pdf = cos(theta) / pi.
vec3 sampleCosineHemisphere(vec2 u) {
  float r = sqrt(u.x);
  float phi = 2.0 * PI * u.y;
  return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
}

// GGX normal distribution sample (half vector around +Z); pdf = D(h) cos(theta_h).
vec3 sampleGgxHalfVector(vec2 u, float alpha) {
  float a2 = alpha * alpha;
  float cosTheta = sqrt((1.0 - u.x) / (1.0 + (a2 - 1.0) * u.x));
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  float phi = 2.0 * PI * u.y;
  return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// Anisotropic GGX half vector around +Z, alpha_t along +X and alpha_b along +Y: the isotropic
// slope stretched; pdf = D(h) cos(theta_h) (sampleGgxDAnisotropic, pdfGgxDAnisotropic).
vec3 sampleGgxAnisotropicHalfVector(vec2 u, float alphaT, float alphaB) {
  float r = sqrt(u.x / max(1.0 - u.x, 1e-7));
  float phi = 2.0 * PI * u.y;
  return normalize(vec3(alphaT * r * cos(phi), alphaB * r * sin(phi), 1.0));
}

mat3 tangentFrame(vec3 n) {
  vec3 up = abs(n.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  vec3 t = normalize(cross(up, n));
  return mat3(t, cross(n, t), n);
}
