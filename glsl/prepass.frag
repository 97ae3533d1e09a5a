// Depth and normal prepass (rendered once per camera, at frame 2, or every frame when
// stochastic transparency changes which surfaces are there): view-space normal and linear
// view depth, read by the occlusion tracer.
#include "chunks/brdf.glsl"
#include "chunks/material.glsl"
uniform mat4 uView;
out vec4 fragGeometry;
void main() {
  vec3 n = normalize(vNormal);
  if (!gl_FrontFacing) n = -n;
  if (uAlphaMode != 0) alphaTest(baseColor().a);
  vec3 viewPos = (uView * vec4(vWorldPos, 1.0)).xyz;
  fragGeometry = vec4(normalize(mat3(uView) * n), -viewPos.z);
}
