// A probe's cube capture (passes/probe_volume.h): the six faces side by side in one strip,
// diffuse light only (chunks/layers.glsl under PN_CAPTURE folds the specular layer into the
// diffuse one), alpha the signed distance to the probe in the volume's diagonals (back faces
// negative: a probe that sees mostly those is buried in geometry). The terms:
// chunks/lighting_common.glsl (the environment's share is the volume's own answer: each
// capture adds a bounce).
#include "chunks/lighting_common.glsl"

uniform int uSingleSided;      // the material is not double-sided: its back faces are walls' insides
uniform int uCaptureFaceSize;  // texels: face i is the square at x = i * size of the strip
flat in int vFace;

out vec4 fragColor;

void main() {
  if (int(gl_FragCoord.x) / uCaptureFaceSize != vFace) discard;  // another face's square
  float probeDistance = length(uViewOrigin.xyz - vWorldPos) / uProbeDiagonal;
  if (!gl_FrontFacing && uSingleSided != 0) {
    fragColor = vec4(0.0, 0.0, 0.0, -probeDistance * uEnvWeight);
    return;
  }
  vec3 v = viewDirection();
  SurfaceInputs s = readSurface(v);
  if (PN_UNLIT != 0 && uUnlit != 0) {
    fragColor = vec4(s.baseColor.rgb * uEnvWeight, probeDistance * uEnvWeight);
    return;
  }
  Layers L = surfaceLayers(s, v);
  // Emissive surfaces light the probes (once, in the first batch), but for the area lights'
  // visible faces: their light is the area lights'.
  fragColor = vec4(surfaceLight(L, s.occlusion) + s.emissive * (uEnvWeight * uIndirectEmission),
                   probeDistance * uEnvWeight);
}
