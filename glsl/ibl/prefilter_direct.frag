// GPU prefilter, rough mips: the exact convolution over every texel of a small source level
// (at most 32 px faces): sum L(l) D(h) (n.l) dOmega / sum D(h) (n.l) dOmega, h = normalize(n+l).
// For wide lobes this is cheaper than importance sampling and keeps small bright sources (a
// sun) where they are instead of smearing them through coarse mips.
#include "chunks/cube_geometry.glsl"
uniform samplerCube uSource;
uniform int uFace;
uniform float uFaceSize;     // of the mip being written
uniform int uSourceSize;     // face size of the source level read
uniform float uSourceLevel;
uniform float uAlpha;
out vec4 fragColor;
void main() {
  vec3 n = cubeDirection(uFace, (floor(gl_FragCoord.xy) + 0.5) / uFaceSize);
  float a2 = uAlpha * uAlpha;
  float inv = 1.0 / float(uSourceSize);
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  for (int f = 0; f < 6; ++f) {
    for (int y = 0; y < 64; ++y) {
      if (y >= uSourceSize) break;
      for (int x = 0; x < 64; ++x) {
        if (x >= uSourceSize) break;
        vec2 st = (vec2(x, y) + 0.5) * inv;
        vec2 c = st * 2.0 - 1.0;
        vec3 l = cubeDirection(f, st);
        float NoL = dot(n, l);
        if (NoL <= 0.0) continue;
        // Texel solid angle on the unit cube face: (2/N)^2 / (1 + sc^2 + tc^2)^(3/2).
        float dOmega = 4.0 * inv * inv * pow(1.0 + dot(c, c), -1.5);
        float NoH = max(dot(n, normalize(n + l)), 0.0);
        float d = (NoH * a2 - NoH) * NoH + 1.0;
        float w = a2 / (PI * d * d) * NoL * dOmega;
        sum += textureLod(uSource, l, uSourceLevel).rgb * w;
        weight += w;
      }
    }
  }
  fragColor = vec4(sum / max(weight, 1e-12), 1.0);
}
