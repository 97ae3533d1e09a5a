// Projects one probe's cube capture (six faces of PN_PROBE_CAPTURE_SIZE^2 texels, side by side
// in a strip: rgb radiance, a signed distance in units of the volume's diagonal, negative on a
// back face) onto its octahedral tile: irradiance (PN_PROBE_MAP 0), the mean and mean square
// distance about each direction (1), or the radiance seen in each direction with alpha 1 where
// that is geometry, 0 where it is sky (2, glossy reflections of the room). Border texels repeat
// the interior texel the octahedral wrap puts next to them, so bilinear lookups never bleed
// into another probe. The caller blends the result into the atlas with the probe's running-mean weight.
#include "chunks/octahedral.glsl"

uniform highp sampler2D uCapture;
uniform vec2 uTileOrigin;        // the tile's lower-left corner in the atlas, in pixels
uniform vec3 uFaceForward[6];
uniform vec3 uFaceRight[6];
uniform vec3 uFaceUp[6];
out vec4 fragColor;

#if PN_PROBE_MAP == 1
const int INTERIOR = PN_PROBE_DEPTH_TEXELS;
#elif PN_PROBE_MAP == 2
const int INTERIOR = PN_PROBE_RADIANCE_TEXELS;
#else
const int INTERIOR = PN_PROBE_IRRADIANCE_TEXELS;
#endif

void main() {
  const int T = INTERIOR + 2;
  ivec2 t = ivec2(gl_FragCoord.xy - uTileOrigin);
  // Border texels: mirror across the edge they sit on (corners take the opposite corner).
  ivec2 s = t;
  bool bx = t.x == 0 || t.x == T - 1, by = t.y == 0 || t.y == T - 1;
  if (bx && by) {
    s = ivec2(t.x == 0 ? T - 2 : 1, t.y == 0 ? T - 2 : 1);
  } else if (bx) {
    s = ivec2(t.x == 0 ? 1 : T - 2, T - 1 - t.y);
  } else if (by) {
    s = ivec2(T - 1 - t.x, t.y == 0 ? 1 : T - 2);
  }
  vec3 n = octDecode((vec2(s - 1) + 0.5) / float(INTERIOR) * 2.0 - 1.0);
  const int C = PN_PROBE_CAPTURE_SIZE;
#if PN_PROBE_MAP == 2
  // The capture's texel in direction n: the face of its major axis, bilinear within the face.
  int face = 0;
  float best = -2.0;
  for (int f = 0; f < 6; ++f) {
    float c = dot(n, uFaceForward[f]);
    if (c > best) {
      best = c;
      face = f;
    }
  }
  vec2 st = vec2(dot(n, uFaceRight[face]), dot(n, uFaceUp[face])) / best;
  vec2 texel = clamp((st * 0.5 + 0.5) * float(C), vec2(0.5), vec2(float(C) - 0.5));
  vec2 size = vec2(textureSize(uCapture, 0));
  vec4 L = textureLod(uCapture, (vec2(float(face * C), 0.0) + texel) / size, 0.0);
  float far = texelFetch(uCapture, ivec2(face * C, 0) + ivec2(texel), 0).a;
  bool finite = all(lessThan(abs(L.rgb), vec3(1e30)));
  fragColor = vec4(finite ? L.rgb : vec3(0.0), abs(far) < 3.5 ? 1.0 : 0.0);
#elif PN_PROBE_MAP == 1
  // Distances about n, weighted by a sharp cosine lobe (about the tile's texel spacing), over
  // 2x2 blocks of the capture (a bilinear lookup at each block's centre averages their
  // distances: a quarter of the work, and a variance a little under the true one, which only
  // makes the visibility test stricter).
  const int H = C / 2;
  vec2 size = vec2(textureSize(uCapture, 0));
  vec2 moments = vec2(0.0);
  float weight = 0.0;
  for (int face = 0; face < 6; ++face) {
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < H; ++x) {
        vec2 st = (vec2(x, y) + 0.5) * (2.0 / float(H)) - 1.0;
        vec3 d = uFaceForward[face] + st.x * uFaceRight[face] + st.y * uFaceUp[face];
        float len2 = dot(d, d);
        float c = dot(n, d) * inversesqrt(len2);
        if (c <= 0.0) continue;
        float w = pow(c, 64.0) / (len2 * sqrt(len2));
        vec2 uv = (vec2(float(face * C), 0.0) + vec2(x, y) * 2.0 + 1.0) / size;
        float r = abs(textureLod(uCapture, uv, 0.0).a);
        if (!(r < 1e30)) continue;  // non-finite: a bad light must not poison the volume
        moments += w * vec2(r, r * r);
        weight += w;
      }
    }
  }
  fragColor = vec4(weight > 0.0 ? moments / weight : vec2(0.0), 0.0, 1.0);
#else
  // E(n) = sum L(w) max(0, n.w) dw over 2x2 blocks (bilinear lookups at their centres: the
  // cosine lobe is smooth), and the share of solid angle that shows back faces: a probe that
  // mostly sees the inside of geometry is marked unusable (alpha 0).
  const int H = C / 2;
  vec2 size = vec2(textureSize(uCapture, 0));
  vec3 e = vec3(0.0);
  float backfaces = 0.0;
  for (int face = 0; face < 6; ++face) {
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < H; ++x) {
        vec2 st = (vec2(x, y) + 0.5) * (2.0 / float(H)) - 1.0;
        vec3 d = uFaceForward[face] + st.x * uFaceRight[face] + st.y * uFaceUp[face];
        float len2 = dot(d, d);
        float dw = (4.0 / float(H * H)) / (len2 * sqrt(len2));
        vec4 L = textureLod(uCapture, (vec2(float(face * C), 0.0) + vec2(x, y) * 2.0 + 1.0) / size, 0.0);
        // Non-finite radiance (a light with a NaN intensity) is skipped, as the accumulation
        // drops such samples.
        if (!all(lessThan(abs(L.rgb), vec3(1e30)))) continue;
        e += L.rgb * (max(dot(n, d), 0.0) * inversesqrt(len2) * dw);
        backfaces += L.a < 0.0 ? dw : 0.0;
      }
    }
  }
  // 4 pi steradians in all; buried probes see back faces in most directions.
  fragColor = vec4(e, backfaces < PN_PROBE_BURIED_SHARE * 4.0 * 3.14159265 ? 1.0 : 0.0);
#endif
}
