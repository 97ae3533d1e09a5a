// Depth-only geometry for shadow maps rendered from one point on an area light.
layout(location = 0) in vec3 aPosition;
// A copy's world matrix as rows (mesh.vert).
layout(location = 6) in vec4 aCopyRow0;
layout(location = 7) in vec4 aCopyRow1;
layout(location = 8) in vec4 aCopyRow2;
uniform mat4 uModel;
uniform mat4 uViewProj;
void main() {
  vec3 local = vec3(dot(aCopyRow0, vec4(aPosition, 1.0)), dot(aCopyRow1, vec4(aPosition, 1.0)),
                    dot(aCopyRow2, vec4(aPosition, 1.0)));
  gl_Position = uViewProj * uModel * vec4(local, 1.0);
}
