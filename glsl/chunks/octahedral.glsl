// Octahedral mapping of unit directions to [-1, 1]^2 (z > 0 in the inner diamond), the layout
// of the probe volume's per-probe maps.
vec2 signNotZero(vec2 v) {
  return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0);
}

vec2 octEncode(vec3 d) {
  d /= abs(d.x) + abs(d.y) + abs(d.z);
  return d.z >= 0.0 ? d.xy : (1.0 - abs(d.yx)) * signNotZero(d.xy);
}

vec3 octDecode(vec2 e) {
  vec3 v = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (v.z < 0.0) v.xy = (1.0 - abs(v.yx)) * signNotZero(v.xy);
  return normalize(v);
}
