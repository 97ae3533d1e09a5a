// Area lights (EXT_lights_area rect and disk; one-sided, Lambertian emitters of luminance L).
// Diffuse: the exact irradiance of the light polygon clipped to the receiver's horizon
// (Lambert's contour integral), so E matches the analytic form factor; a disk is an
// area-preserving 16-gon. Specular: Karis' most representative point with the lobe widened by
// the light's size and renormalised, scaled by the same irradiance.
const int DISK_SEGMENTS = 16;

struct AreaLight {
  vec3 position;  // centre
  vec3 direction; // emission direction (unit)
  vec3 right;     // unit, along width
  vec3 up;        // unit, along height
  vec2 size;      // rect: width, height; disk: diameter, diameter
  int shape;      // PN_LIGHT_RECT or PN_LIGHT_DISK (scene/light_kinds.h shaderCode)
};

// Contribution of the edge a -> b (unit vectors from the shading point) to the contour sum:
// theta * dot(normalize(cross(a, b)), n). theta / sin(theta) comes from the rational fit of
// Hill and Heitz (2016) instead of atan, which costs a software rasterizer far more than the
// rest of the integral; the fit's relative error stays under 0.1 %.
float edgeTerm(vec3 a, vec3 b, vec3 n) {
  float x = dot(a, b);
  float y = abs(x);
  float v = (0.8543985 + (0.4965155 + 0.0145206 * y) * y) / (3.4175940 + (4.1616724 + y) * y);
  // The fit gives theta / (2 pi sin(theta)).
  float thetaOverSin = x > 0.0 ? v : 0.5 * inversesqrt(max(1.0 - x * x, 1e-7)) - v;
  return (2.0 * PI) * thetaOverSin * dot(cross(a, b), n);
}

// Irradiance per unit luminance from the light at p with normal n (0 behind the emitter).
// The polygon's vertices are generated on the fly, c + cos(t) A + sin(t) B with t stepping by
// 2 pi / N (a rotation recurrence), and clipped to the horizon edge by edge: no local arrays,
// which a SIMD software rasterizer would spill to memory per lane. A rect is the N = 4 case
// (A, B = sqrt 2 times the half extents, starting at 225 degrees); a disk an area-preserving
// 16-gon, r' = r sqrt(2 pi / (N sin(2 pi / N))).
float areaLightIrradiance(AreaLight L, vec3 p, vec3 n) {
  if (dot(p - L.position, L.direction) <= 0.0) return 0.0;
  vec3 c = L.position - p;
  vec3 A, B;
  vec2 cs;     // (cos t, sin t) of the current vertex
  vec2 step;   // (cos, sin) of the step angle
  int count;
  if (L.shape == PN_LIGHT_DISK) {
    float r = 0.5 * L.size.x * 1.0130;  // N = 16
    A = r * L.right;
    B = r * L.up;
    cs = vec2(1.0, 0.0);
    step = vec2(0.92387953, 0.38268343);
    count = DISK_SEGMENTS;
  } else {
    A = (0.5 * L.size.x) * L.right;
    B = (0.5 * L.size.y) * L.up;
    cs = vec2(-1.0, -1.0);  // unnormalised corner signs: the 90 degree rotation stays exact
    step = vec2(0.0, 1.0);
    count = 4;
  }
  vec3 first = c + cs.x * A + cs.y * B;
  vec3 a = first;
  float da = dot(a, n);
  float sum = 0.0;
  bool haveExit = false, haveEnter = false;
  vec3 exitPt = vec3(0.0), enterPt = vec3(0.0);
  // Branch-free clipping: each edge keeps its part above the horizon (a or b replaced by the
  // crossing x) and costs one edge term. A SIMD rasterizer runs both sides of a branch on a
  // per-pixel value, so the former three-way branch evaluated three terms an edge.
  for (int i = 0; i < DISK_SEGMENTS; ++i) {
    if (i >= count) break;
    cs = vec2(cs.x * step.x - cs.y * step.y, cs.x * step.y + cs.y * step.x);
    vec3 b = i + 1 == count ? first : c + cs.x * A + cs.y * B;
    float db = dot(b, n);
    bool aUp = da >= 0.0, bUp = db >= 0.0;
    float denom = da - db;
    vec3 x = a + (b - a) * clamp(da / (abs(denom) > 1e-20 ? denom : 1e-20), 0.0, 1.0);
    float term = edgeTerm(normalize(aUp ? a : x), normalize(bUp ? b : x), n);
    sum += aUp || bUp ? term : 0.0;
    bool exits = aUp && !bUp, enters = bUp && !aUp;
    exitPt = exits ? x : exitPt;
    enterPt = enters ? x : enterPt;
    haveExit = haveExit || exits;
    haveEnter = haveEnter || enters;
    a = b;
    da = db;
  }
  float closing = edgeTerm(normalize(exitPt), normalize(enterPt), n);
  sum += haveExit && haveEnter ? closing : 0.0;
  return 0.5 * abs(sum);
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
  if (L.shape == PN_LIGHT_DISK) {
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
void evaluateAreaLight(AreaLight L, vec3 p, vec3 n, vec3 v, vec3 f0, float f90, float alpha,
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
  float area = L.shape == PN_LIGHT_DISK ? 0.785398 * L.size.x * L.size.x : L.size.x * L.size.y;
  float equivalentRadius = sqrt(area / PI);
  float widened = min(1.0, alpha + equivalentRadius / (2.0 * dist));
  float norm = (alpha / widened) * (alpha / widened);
  // D keeps its shape but its peak drops to that of the widened lobe: (alpha / alpha')^2.
  specular = specularBrdf(n, v, l, f0, f90, alpha, norm) * irradiance;
}
