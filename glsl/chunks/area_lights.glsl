// Area lights (EXT_lights_area rect and disk; one-sided, Lambertian emitters of luminance L).
// Diffuse: the exact irradiance of the light polygon clipped to the receiver's horizon
// (Lambert's contour integral), so E matches the analytic form factor; a disk is an
// area-preserving 16-gon. Specular: Karis' most representative point with the lobe widened by
// the light's size and renormalised, scaled by the same irradiance.
const int DISK_SEGMENTS = 16;
const int MAX_POLY = 17;

struct AreaLight {
  vec3 position;  // centre
  vec3 direction; // emission direction (unit)
  vec3 right;     // unit, along width
  vec3 up;        // unit, along height
  vec2 size;      // rect: width, height; disk: diameter, diameter
  bool disk;
};

// Contribution of the edge a -> b (unit vectors from the shading point) to the contour sum.
float edgeTerm(vec3 a, vec3 b, vec3 n) {
  vec3 c = cross(a, b);
  float len = length(c);
  if (len < 1e-9) return 0.0;
  return atan(len, dot(a, b)) * dot(c / len, n);
}

// Irradiance per unit luminance at a point (vertices relative to it) with normal n.
float polygonIrradiance(vec3 verts[MAX_POLY], int count, vec3 n) {
  float sum = 0.0;
  bool haveExit = false, haveEnter = false;
  vec3 exitPt = vec3(0.0), enterPt = vec3(0.0);
  for (int i = 0; i < MAX_POLY; ++i) {
    if (i >= count) break;
    vec3 a = verts[i];
    vec3 b = verts[i + 1 == count ? 0 : i + 1];
    float da = dot(a, n), db = dot(b, n);
    if (da >= 0.0 && db >= 0.0) {
      sum += edgeTerm(normalize(a), normalize(b), n);
    } else if (da >= 0.0 && db < 0.0) {
      vec3 x = a + (b - a) * (da / (da - db));
      sum += edgeTerm(normalize(a), normalize(x), n);
      exitPt = x;
      haveExit = true;
    } else if (da < 0.0 && db >= 0.0) {
      vec3 x = a + (b - a) * (da / (da - db));
      sum += edgeTerm(normalize(x), normalize(b), n);
      enterPt = x;
      haveEnter = true;
    }
  }
  if (haveExit && haveEnter) sum += edgeTerm(normalize(exitPt), normalize(enterPt), n);
  return 0.5 * abs(sum);
}

int areaLightPolygon(AreaLight L, vec3 p, out vec3 verts[MAX_POLY]) {
  vec3 c = L.position - p;
  if (L.disk) {
    // Area-preserving regular polygon: r' = r sqrt(2 pi / (N sin(2 pi / N))).
    float r = 0.5 * L.size.x * 1.0130;  // N = 16
    for (int i = 0; i < DISK_SEGMENTS; ++i) {
      float phi = float(i) * (2.0 * PI / float(DISK_SEGMENTS));
      verts[i] = c + r * (cos(phi) * L.right + sin(phi) * L.up);
    }
    return DISK_SEGMENTS;
  }
  vec3 hx = 0.5 * L.size.x * L.right, hy = 0.5 * L.size.y * L.up;
  verts[0] = c - hx - hy;
  verts[1] = c + hx - hy;
  verts[2] = c + hx + hy;
  verts[3] = c - hx + hy;
  return 4;
}

// Irradiance per unit luminance from the light at p with normal n (0 behind the emitter).
float areaLightIrradiance(AreaLight L, vec3 p, vec3 n) {
  if (dot(p - L.position, L.direction) <= 0.0) return 0.0;
  vec3 verts[MAX_POLY];
  int count = areaLightPolygon(L, p, verts);
  return polygonIrradiance(verts, count, n);
}

// Karis' most representative point: where the reflection ray meets the light, clamped to
// its shape; if the ray points away, the shape point nearest to the ray's projection.
vec3 representativePoint(AreaLight L, vec3 p, vec3 r) {
  float denom = dot(r, L.direction);
  vec3 q;
  if (denom < -1e-4) {
    q = p + r * (dot(L.position - p, L.direction) / denom);
  } else {
    q = p + r * length(L.position - p);
    q -= dot(q - L.position, L.direction) * L.direction;
  }
  vec3 d = q - L.position;
  vec2 local = vec2(dot(d, L.right), dot(d, L.up));
  if (L.disk) {
    float rad = 0.5 * L.size.x;
    float len = length(local);
    if (len > rad) local *= rad / len;
  } else {
    local = clamp(local, -0.5 * L.size, 0.5 * L.size);
  }
  return L.position + local.x * L.right + local.y * L.up;
}

// Radiance reflected toward v per unit light luminance, split into diffuse irradiance
// (to be multiplied by albedo / pi) and specular.
void evaluateAreaLight(AreaLight L, vec3 p, vec3 n, vec3 v, vec3 f0, float alpha,
                       out float irradiance, out vec3 specular) {
  irradiance = areaLightIrradiance(L, p, n);
  specular = vec3(0.0);
  if (irradiance <= 0.0) return;
  vec3 r = reflect(-v, n);
  vec3 q = representativePoint(L, p, r);
  vec3 toQ = q - p;
  float dist = max(length(toQ), 1e-4);
  vec3 l = toQ / dist;
  if (dot(n, l) <= 0.0) return;
  float area = L.disk ? 0.785398 * L.size.x * L.size.x : L.size.x * L.size.y;
  float equivalentRadius = sqrt(area / PI);
  float widened = min(1.0, alpha + equivalentRadius / (2.0 * dist));
  float norm = (alpha / widened) * (alpha / widened);
  // D keeps its shape but its peak drops to that of the widened lobe: (alpha / alpha')^2.
  specular = specularBrdf(n, v, l, f0, alpha, norm) * irradiance;
}
