// Cube-map and panorama geometry, mirroring renderer/src/ibl/cubemap.cpp exactly: faces
// +X, -X, +Y, -Y, +Z, -Z with the GL major-axis table, and the panorama convention of
// docs/ibl.md (centre column +X, u = 0.75 toward +Z, top row +Y).
vec3 cubeDirection(int face, vec2 st) {
  vec2 c = st * 2.0 - 1.0;  // sc, tc
  vec3 d;
  if (face == 0) d = vec3(1.0, -c.y, -c.x);
  else if (face == 1) d = vec3(-1.0, -c.y, c.x);
  else if (face == 2) d = vec3(c.x, 1.0, c.y);
  else if (face == 3) d = vec3(c.x, -1.0, -c.y);
  else if (face == 4) d = vec3(c.x, -c.y, 1.0);
  else d = vec3(-c.x, -c.y, -1.0);
  return normalize(d);
}

vec2 panoramaCoord(vec3 d) {
  d = normalize(d);
  float u = 0.5 + atan(d.z, d.x) * (0.5 * INV_PI);
  float v = 0.5 - asin(clamp(d.y, -1.0, 1.0)) * INV_PI;
  return vec2(fract(u), v);
}
