// GPU prefilter, step 2: one face of one specular mip. GGX importance sampling with N = V = R
// (Karis 2013), filtered importance sampling (Krivanek & Colbert 2008): each sample reads the
// source mip whose texel solid angle matches the sample's share of the lobe.
#include "chunks/cube_geometry.glsl"
uniform samplerCube uSource;
uniform int uFace;
uniform float uFaceSize;       // of the mip being written
uniform float uSourceSize;     // mip-0 face size of the source
uniform float uAlpha;          // GGX alpha = roughness^2
uniform int uSamples;
uniform float uMaxLod;         // keeps at least 4x4 texels per face: coarser levels smear
                               // a bright source over a whole face
out vec4 fragColor;

vec2 hammersley(int i, int n) {
  uint b = uint(i);
  b = (b << 16u) | (b >> 16u);
  b = ((b & 0x55555555u) << 1u) | ((b & 0xAAAAAAAAu) >> 1u);
  b = ((b & 0x33333333u) << 2u) | ((b & 0xCCCCCCCCu) >> 2u);
  b = ((b & 0x0F0F0F0Fu) << 4u) | ((b & 0xF0F0F0F0u) >> 4u);
  b = ((b & 0x00FF00FFu) << 8u) | ((b & 0xFF00FF00u) >> 8u);
  return vec2((float(i) + 0.5) / float(n), float(b) * 2.3283064365386963e-10);
}

void main() {
  vec3 n = cubeDirection(uFace, (floor(gl_FragCoord.xy) + 0.5) / uFaceSize);
  vec3 up = abs(n.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 tx = normalize(cross(up, n));
  vec3 ty = cross(n, tx);
  float a2 = uAlpha * uAlpha;
  float texelSolidAngle = 4.0 * PI / (6.0 * uSourceSize * uSourceSize);
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  for (int i = 0; i < 4096; ++i) {
    if (i >= uSamples) break;
    vec2 u = hammersley(i, uSamples);
    float cosT = sqrt((1.0 - u.y) / (1.0 + (a2 - 1.0) * u.y));
    float sinT = sqrt(max(0.0, 1.0 - cosT * cosT));
    float phi = 2.0 * PI * u.x;
    vec3 h = tx * (sinT * cos(phi)) + ty * (sinT * sin(phi)) + n * cosT;
    vec3 l = 2.0 * dot(n, h) * h - n;
    float NoL = dot(n, l);
    if (NoL <= 0.0) continue;
    // pdf of l = D(h) (n.h) / (4 v.h) = D(h) / 4 with n = v.
    float f = (cosT * a2 - cosT) * cosT + 1.0;
    float D = a2 / (PI * f * f);
    float sampleSolidAngle = 1.0 / (float(uSamples) * D * 0.25 + 1e-9);
    float lod = clamp(0.5 * log2(sampleSolidAngle / texelSolidAngle), 0.0, uMaxLod);
    sum += textureLod(uSource, l, lod).rgb * NoL;
    weight += NoL;
  }
  fragColor = vec4(sum / max(weight, 1e-9), 1.0);
}
