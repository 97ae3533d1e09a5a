// A single triangle covering the viewport; vUv spans [0, 1] over the screen.
// PN_FAR_PLANE (0 or 1) puts it at the far plane (the background).
out vec2 vUv;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  vUv = p;
#if PN_FAR_PLANE
  // At the far plane, so a depth test LEQUAL shades only pixels no geometry covered.
  gl_Position = vec4(p * 2.0 - 1.0, 1.0, 1.0);
#else
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
#endif
}
