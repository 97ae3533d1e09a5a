// GPU prefilter, step 1: one face of mip 0 from the panorama, 2x2 supersampled per texel from
// the panorama's mip level whose texels match the cube texel's footprint.
#include "chunks/cube_geometry.glsl"
uniform sampler2D uPanorama;
uniform int uFace;
uniform float uFaceSize;
uniform float uLod;
out vec4 fragColor;
void main() {
  vec3 sum = vec3(0.0);
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      vec2 st = (floor(gl_FragCoord.xy) + vec2(0.25 + 0.5 * float(i), 0.25 + 0.5 * float(j))) / uFaceSize;
      sum += textureLod(uPanorama, panoramaCoord(cubeDirection(uFace, st)), uLod).rgb;
    }
  }
  fragColor = vec4(sum * 0.25, 1.0);
}
