// Playback's pose (passes/deform_pass.cpp): a played primitive's vertices from the file's rest
// data, moved by its morph targets' weights, then by its joints, and captured by transform
// feedback into the buffers every pass draws (one vertex a point, nothing rasterized). The
// order and the normal's inverse transpose are the loader's (scene/gltf_morph.cpp,
// scene/gltf_skin.cpp), so a played pose draws as the still loaded at that time.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec4 aTangent;
layout(location = 3) in vec4 aJoints;
layout(location = 4) in vec4 aWeights;

#if PN_MORPH
// Displacements: texel (target * 3 + part) * uVertexCount + vertex, rows of uMorphWidth.
uniform highp sampler2D uMorphs;
uniform vec4 uMorphWeights[PN_MAX_MORPH_TARGETS / 4];
uniform int uMorphTargets;
uniform int uVertexCount;
uniform int uMorphWidth;

vec3 displacement(int target, int part) {
  int texel = (target * 3 + part) * uVertexCount + gl_VertexID;
  return texelFetch(uMorphs, ivec2(texel % uMorphWidth, texel / uMorphWidth), 0).xyz;
}
#endif
#if PN_SKIN
// Joint j's matrix as three rows of its affine part: texels (0..2, j).
uniform highp sampler2D uJoints;
uniform int uJointCount;

mat4 joint(float index) {
  int j = clamp(int(index), 0, uJointCount - 1);
  vec4 r0 = texelFetch(uJoints, ivec2(0, j), 0), r1 = texelFetch(uJoints, ivec2(1, j), 0),
       r2 = texelFetch(uJoints, ivec2(2, j), 0);
  return transpose(mat4(r0, r1, r2, vec4(0.0, 0.0, 0.0, 1.0)));
}
#endif

out vec3 vPosition;
out vec3 vNormal;
#if PN_TANGENTS
out vec4 vTangent;
#endif

void main() {
  vec3 position = aPosition;
  vec3 normal = aNormal;
  vec3 tangent = aTangent.xyz;
#if PN_MORPH
  for (int t = 0; t < uMorphTargets; ++t) {
    float w = uMorphWeights[t / 4][t % 4];
    if (w == 0.0) continue;
    position += w * displacement(t, 0);
    normal += w * displacement(t, 1);
    tangent += w * displacement(t, 2);
  }
  if (length(normal) > 0.0) normal = normalize(normal);
#endif
#if PN_SKIN
  mat4 m = aWeights.x * joint(aJoints.x) + aWeights.y * joint(aJoints.y) +
           aWeights.z * joint(aJoints.z) + aWeights.w * joint(aJoints.w);
  position = (m * vec4(position, 1.0)).xyz;
  mat3 linear = mat3(m);
  vec3 n = transpose(inverse(linear)) * normal;
  if (length(n) > 0.0) normal = normalize(n);
  vec3 t = linear * tangent;
  if (length(t) > 0.0) tangent = normalize(t);
#endif
  vPosition = position;
  vNormal = normal;
#if PN_TANGENTS
  vTangent = vec4(tangent, aTangent.w);
#endif
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
