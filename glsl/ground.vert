// The shadow-catching ground (passes/ground_shadow.cpp): a square on the plane under the
// scene, its four corners from gl_VertexID (a triangle strip, no vertex buffer). It writes
// every varying mesh.vert does, so the lighting chunks link as they do there.
uniform mat4 uViewProj;
uniform vec3 uGroundCenter;  // the square's centre, on the plane y = uGroundCenter.y
uniform float uGroundHalf;   // half its side

out vec3 vWorldPos;
out vec3 vNormal;
out vec4 vTangent;
out vec2 vUv0;
out vec2 vUv1;
out vec4 vColor;

void main() {
  // Strip order (-,-), (+,-), (-,+), (+,+) in (x, z): counter-clockwise seen from above.
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
  vec3 world = uGroundCenter + vec3(corner.x, 0.0, -corner.y) * uGroundHalf;
  vWorldPos = world;
  vNormal = vec3(0.0, 1.0, 0.0);
  vTangent = vec4(1.0, 0.0, 0.0, 1.0);
  vUv0 = corner * 0.5 + 0.5;
  vUv1 = vUv0;
  vColor = vec4(1.0);
  gl_Position = uViewProj * vec4(world, 1.0);
}
