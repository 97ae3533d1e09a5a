// Depth-only geometry for shadow maps rendered from one point on an area light.
layout(location = 0) in vec3 aPosition;
uniform mat4 uModel;
uniform mat4 uViewProj;
void main() { gl_Position = uViewProj * uModel * vec4(aPosition, 1.0); }
