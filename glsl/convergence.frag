// An automatic view's convergence measure (progressive/convergence.h): per tile of
// PN_TILE x PN_TILE pixels, the RMS change of the displayed image (in 8-bit steps) from a kept
// checkpoint's displayed image (checkpoint_snapshot.frag) to that of the running mean, and its
// largest change (one channel of one pixel). One output texel a tile: (RMS, values counted,
// largest, 1).
#include "chunks/displayed.glsl"
uniform sampler2D uCurrent;   // the running mean, radiance
uniform sampler2D uPrevious;  // a kept checkpoint, displayed
out vec4 fragColor;

void main() {
  ivec2 size = textureSize(uCurrent, 0);
  ivec2 base = ivec2(gl_FragCoord.xy) * PN_TILE;
  float sum = 0.0;
  float count = 0.0;
  float largest = 0.0;
  for (int y = 0; y < PN_TILE; ++y) {
    for (int x = 0; x < PN_TILE; ++x) {
      ivec2 p = base + ivec2(x, y);
      if (p.x >= size.x || p.y >= size.y) continue;
      vec3 d = (displayed(texelFetch(uCurrent, p, 0)) - texelFetch(uPrevious, p, 0).rgb) * 255.0;
      sum += dot(d, d);
      vec3 a = abs(d);
      largest = max(largest, max(a.r, max(a.g, a.b)));
      count += 3.0;
    }
  }
  fragColor = vec4(sqrt(sum / max(count, 1.0)), count, largest, 1.0);
}
