// Geometry of every scene pass (prepass, lighting). The projection carries the frame's
// sub-pixel jitter.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec4 aTangent;
layout(location = 3) in vec2 aUv0;
layout(location = 4) in vec2 aUv1;
layout(location = 5) in vec4 aColor;
// EXT_mesh_gpu_instancing: the copy's world matrix as rows (the identity for other items, whose
// uModel is their world matrix; copies have uModel the identity).
layout(location = 6) in vec4 aCopyRow0;
layout(location = 7) in vec4 aCopyRow1;
layout(location = 8) in vec4 aCopyRow2;

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
  mat4 copy = transpose(mat4(aCopyRow0, aCopyRow1, aCopyRow2, vec4(0.0, 0.0, 0.0, 1.0)));
  mat3 linear = mat3(copy);
  // The copy's normal matrix as its cofactor matrix (its inverse transpose times the
  // determinant): three cross products, the determinant's sign kept for mirrored copies.
  mat3 cofactor = mat3(cross(linear[1], linear[2]), cross(linear[2], linear[0]),
                       cross(linear[0], linear[1]));
  float mirror = dot(linear[0], cofactor[0]) < 0.0 ? -1.0 : 1.0;
  vec4 world = uModel * (copy * vec4(aPosition, 1.0));
  vWorldPos = world.xyz;
  vNormal = uNormalMatrix * (cofactor * aNormal) * mirror;
  vTangent = vec4(mat3(uModel) * (linear * aTangent.xyz), aTangent.w);
  vUv0 = aUv0;
  vUv1 = aUv1;
  vColor = aColor;
#if defined(PN_CAPTURE) && PN_CAPTURE
  // Instance 6 c + i: copy c (its rows advance every six instances), face i.
  int face = gl_InstanceID % 6;
  vFace = face;
  vec4 clip = uFaceViewProj[face] * world;
  // Face i's square is x in [-1 + 2i/6, -1 + 2(i+1)/6] of the strip's normalized coordinates.
  clip.x = clip.x / 6.0 + clip.w * ((2.0 * float(face) + 1.0) / 6.0 - 1.0);
  gl_Position = clip;
#else
  gl_Position = uViewProj * world;
#endif
}
