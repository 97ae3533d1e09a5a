// Depth and normal prepass (rendered once per camera, at frame 2): view-space normal and
// linear view depth, read by the occlusion tracer.
#include "chunks/brdf.glsl"
#include "chunks/material.glsl"
uniform mat4 uView;
out vec4 fragGeometry;
void main() {
  vec3 n = normalize(vNormal);
  if (!gl_FrontFacing) n = -n;
  if (uAlphaMode == 1) {
    float a = uBaseColorFactor.a * vColor.a;
    if (hasTexture(SLOT_BASE)) a *= texture(uBaseColorTex, slotUv(SLOT_BASE)).a;
    if (a < uAlphaCutoff) discard;
  }
  vec3 viewPos = (uView * vec4(vWorldPos, 1.0)).xyz;
  fragGeometry = vec4(normalize(mat3(uView) * n), -viewPos.z);
}
