// Geometry of every scene pass (prepass, lighting). The projection carries the frame's
// sub-pixel jitter.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec4 aTangent;
layout(location = 3) in vec2 aUv0;
layout(location = 4) in vec2 aUv1;
layout(location = 5) in vec4 aColor;

uniform mat4 uModel;
uniform mat3 uNormalMatrix;
uniform mat4 uViewProj;

out vec3 vWorldPos;
out vec3 vNormal;
out vec4 vTangent;
out vec2 vUv0;
out vec2 vUv1;
out vec4 vColor;
#if defined(PN_CAPTURE) && PN_CAPTURE
// A probe capture draws each item once for all six cube faces (instance i: face i), side by
// side in one strip: one draw call instead of six, which is what a capture costs on a
// software rasterizer. The fragment shader drops what spills into a neighbour's square.
uniform mat4 uFaceViewProj[6];
flat out int vFace;
#endif
// The lighting pass may draw over a depth-only pass of the same geometry with LEQUAL: the
// positions must come out bit-identical in both programs.
invariant gl_Position;

void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorldPos = world.xyz;
  vNormal = uNormalMatrix * aNormal;
  vTangent = vec4(mat3(uModel) * aTangent.xyz, aTangent.w);
  vUv0 = aUv0;
  vUv1 = aUv1;
  vColor = aColor;
#if defined(PN_CAPTURE) && PN_CAPTURE
  vFace = gl_InstanceID;
  vec4 clip = uFaceViewProj[gl_InstanceID] * world;
  // Face i's square is x in [-1 + 2i/6, -1 + 2(i+1)/6] of the strip's normalized coordinates.
  clip.x = clip.x / 6.0 + clip.w * ((2.0 * float(gl_InstanceID) + 1.0) / 6.0 - 1.0);
  gl_Position = clip;
#else
  gl_Position = uViewProj * world;
#endif
}
