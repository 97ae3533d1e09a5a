// Probe volume (passes/probe_volume.h): irradiance probes on a grid over the scene, each with
// an octahedral map of irradiance (alpha: 1 once captured and not buried in geometry) and one
// of the mean and mean square distance to what it sees (in units of the volume's diagonal).
// A third map holds the radiance the probe sees (alpha 1 where that is geometry, 0 where it
// is sky), for glossy reflections of the room.
// A shading point blends four surrounding probes: its barycentric weights in the tetrahedron of
// its grid cell that holds it, times a soft backface weight (probes behind the surface count
// less), times Chebyshev's bound on the probability that the probe sees the point (no light
// through walls), as in DDGI (Majercik et al., JCGT 2019) and Eevee's irradiance grid.
#include "chunks/octahedral.glsl"

// PN_PROBES (a generated define, 1 while the volume is on) guards every lookup.
uniform vec3 uProbeOrigin;
uniform vec3 uProbeSpacing;
uniform vec3 uProbeCounts;  // whole numbers
uniform float uProbeDiagonal;
uniform int uProbeColumns;
uniform int uProbeRows;
// The three maps in one texture (passes/probe_volume.h, atlasLayout): radiance tiles at the
// origin, depth tiles to their right, irradiance tiles above the depth tiles.
uniform sampler2D uProbeAtlas;

// The atlas position of direction `oct` (octEncode's) in a probe's tile (its column and row,
// probeTile) of the map whose tiles have `interior` texels inside a one-texel border and start
// at `origin`.
vec2 probeAtlasUv(vec2 tile, vec2 oct, float interior, vec2 origin, vec2 atlasSize) {
  vec2 corner = origin + tile * (interior + 2.0);
  return (corner + 1.0 + (oct * 0.5 + 0.5) * interior) / atlasSize;
}

// The atlas origins of the depth and irradiance tiles (radiance tiles start at 0).
vec2 probeDepthOrigin() {
  return vec2(float(uProbeColumns * (PN_PROBE_RADIANCE_TEXELS + 2)), 0.0);
}
vec2 probeIrradianceOrigin() {
  return probeDepthOrigin() + vec2(0.0, float(uProbeRows * (PN_PROBE_DEPTH_TEXELS + 2)));
}
// Probe (column, row)'s relocation offset (units of the spacing): one texel a probe above the
// maps.
vec3 probeOffset(vec2 tile) {
  int maps = max(uProbeRows * (PN_PROBE_RADIANCE_TEXELS + 2),
                 uProbeRows * (PN_PROBE_DEPTH_TEXELS + PN_PROBE_IRRADIANCE_TEXELS + 4));
  return texelFetch(uProbeAtlas, ivec2(tile) + ivec2(0, maps), 0).xyz;
}

// A lookup at p (normal n, v toward the viewer): the point q it is made from, off the surface
// and mostly toward the viewer so that it does not start inside the wall (returned), and the
// four probes around q with their barycentric weights. Four, not eight: the grid cell is split
// into six tetrahedra along its main diagonal (Kuhn), and the point's barycentric weights in
// its own tetrahedron interpolate linearly and continuously. Half the texture fetches of
// trilinear weights, which a software rasterizer pays for at every pixel.
vec3 probeTetrahedron(vec3 p, vec3 n, vec3 v, out ivec3 cells[4], out float tri[4]) {
  float minSpacing = min(uProbeSpacing.x, min(uProbeSpacing.y, uProbeSpacing.z));
  vec3 q = p + (0.2 * n + 0.15 * v) * minSpacing;
  vec3 g = (q - uProbeOrigin) / uProbeSpacing;
  ivec3 last = ivec3(uProbeCounts + 0.5) - 1;
  ivec3 base = clamp(ivec3(floor(g)), ivec3(0), max(last - 1, ivec3(0)));
  vec3 f = clamp(g - vec3(base), 0.0, 1.0);
  ivec3 ea, eb;  // the axes of the largest and second-largest fraction
  if (f.x >= f.y && f.x >= f.z) {
    ea = ivec3(1, 0, 0);
    eb = f.y >= f.z ? ivec3(0, 1, 0) : ivec3(0, 0, 1);
  } else if (f.y >= f.z) {
    ea = ivec3(0, 1, 0);
    eb = f.x >= f.z ? ivec3(1, 0, 0) : ivec3(0, 0, 1);
  } else {
    ea = ivec3(0, 0, 1);
    eb = f.x >= f.y ? ivec3(1, 0, 0) : ivec3(0, 1, 0);
  }
  float fa = dot(f, vec3(ea)), fb = dot(f, vec3(eb)), fc = f.x + f.y + f.z - fa - fb;
  cells[0] = base;
  cells[1] = min(base + ea, last);
  cells[2] = min(base + ea + eb, last);
  cells[3] = min(base + ivec3(1), last);
  tri[0] = 1.0 - fa;
  tri[1] = fa - fb;
  tri[2] = fb - fc;
  tri[3] = fc;
  return q;
}

// The column and row of grid cell c's tiles in each map. In floats: a software rasterizer has
// no vector integer division, and the index's % and / ran lane by lane, several times a probe.
vec2 probeTile(ivec3 c) {
  float index = dot(vec3(c), vec3(1.0, uProbeCounts.x, uProbeCounts.x * uProbeCounts.y));
  float columns = float(uProbeColumns);
  float row = floor((index + 0.5) / columns);
  return vec2(index - row * columns, row);
}

// How much the probe at grid cell c (where relocation moved it) counts for a surface point p
// with normal n looked up from q: a soft backface weight (probes behind the surface count less)
// times Chebyshev's bound on the probability that the probe sees q (no light through walls),
// small weights crushed (a barely visible probe should not tint the result).
float probeVisibility(ivec3 c, vec2 tile, vec3 p, vec3 q, vec3 n, vec2 atlasSize) {
  vec3 probePos = uProbeOrigin + (vec3(c) + probeOffset(tile)) * uProbeSpacing;
  float back = (dot(normalize(probePos - p), n) + 1.0) * 0.5;
  float w = back * back + 0.05;
  vec3 fromProbe = q - probePos;
  float dist = length(fromProbe);
  vec2 m = textureLod(uProbeAtlas,
                      probeAtlasUv(tile, octEncode(dist > 0.0 ? fromProbe / dist : n),
                                   float(PN_PROBE_DEPTH_TEXELS), probeDepthOrigin(), atlasSize),
                      0.0)
               .rg;
  float d = dist / uProbeDiagonal;
  if (d > m.x) {
    float variance = abs(m.y - m.x * m.x);
    float e = d - m.x;
    float chebyshev = variance / (variance + e * e);
    w *= chebyshev * chebyshev * chebyshev;
  }
  w = max(w, 1e-5);
  if (w < 0.2) w *= w * w * 25.0;
  return w;
}

// How far the usable probes' answer is trusted, from their share of the barycentric weight
// (`coverage`): wholly from kProbeTrustedCoverage on, the environment's answer mixed in for
// the rest below it. Barycentric weights are linear over a cell, so the mix is continuous;
// renormalizing over the usable probes alone switched to the environment only where none was
// left, a hard seam along the cells around buried probes (a rectangle across the milk truck's
// side, a 20 % step on a block's face in ProbeVolumeGLTest). Mixing by the visibility-weighted
// share instead left a step where the one usable probe's view of the point is cut off, and
// mixing by the whole coverage darkened an interior's walls by its buried probes (its
// environment is no answer for its rooms): from a quarter on, the probes answer alone.
const float kProbeTrustedCoverage = 0.25;
float probeTrust(float coverage) { return clamp(coverage / kProbeTrustedCoverage, 0.0, 1.0); }

// Irradiance at p for normal n, seen from direction v (unit, toward the viewer), from the
// usable probes (captured and not buried in geometry), and (alpha) how far it is trusted
// (probeTrust): the caller mixes the environment's answer in for the rest,
// mix(E_env, rgb, a). Outside captures, and with `glossy`, also the probes' radiance toward r
// (rgb) and the share of it that is geometry (a, the trust included). `weights`: the four
// probes' weights (probeTetrahedron's order), the usable ones' scaled to the trust and the
// rest of it spread over the unusable ones (the environment's share), which the per-view
// cache keeps for the occlusion rays' control variate.
vec4 probeIrradianceWeights(vec3 p, vec3 n, vec3 v, vec3 r, bool glossy, out vec4 radiance,
                            out vec4 weights) {
  // n and r are the same for every probe: encode them once.
  vec2 octN = octEncode(n);
  vec2 octR = octEncode(r);
  ivec3 cells[4];
  float tri[4];
  vec3 q = probeTetrahedron(p, n, v, cells, tri);
  vec2 atlasSize = vec2(textureSize(uProbeAtlas, 0));
  vec4 radSum = vec4(0.0);
  vec4 usableWeights = vec4(0.0);
  vec4 unusableTri = vec4(0.0);
  vec3 sum = vec3(0.0);
  float weightSum = 0.0;
  float coverage = 0.0;
  for (int i = 0; i < 4; ++i) {
    vec2 tile = probeTile(cells[i]);
    vec4 irr = textureLod(uProbeAtlas,
                          probeAtlasUv(tile, octN, float(PN_PROBE_IRRADIANCE_TEXELS),
                                       probeIrradianceOrigin(), atlasSize),
                          0.0);
    if (irr.a <= 0.5) {
      unusableTri[i] = tri[i];
      continue;
    }
    float w = tri[i] * probeVisibility(cells[i], tile, p, q, n, atlasSize);
    coverage += tri[i];
    sum += w * irr.rgb;
    weightSum += w;
    usableWeights[i] = w;
#if !PN_CAPTURE
    if (glossy) {
      vec4 rad = textureLod(uProbeAtlas,
                            probeAtlasUv(tile, octR, float(PN_PROBE_RADIANCE_TEXELS), vec2(0.0),
                                         atlasSize),
                            0.0);
      radSum += (w * rad.a) * vec4(rad.rgb, 1.0);
    }
#endif
  }
  float trust = weightSum > 0.0 ? probeTrust(coverage) : 0.0;
  float unusable = dot(unusableTri, vec4(1.0));
  weights = (weightSum > 0.0 ? usableWeights * (trust / weightSum) : vec4(0.0)) +
            (unusable > 0.0 ? unusableTri * ((1.0 - trust) / unusable) : vec4(0.0));
  radiance = radSum.a > 0.0 ? vec4(radSum.rgb / radSum.a, trust * radSum.a / weightSum)
                            : vec4(0.0);
  return weightSum > 0.0 ? vec4(sum / weightSum, trust) : vec4(0.0);
}

vec4 probeIrradiance(vec3 p, vec3 n, vec3 v, vec3 r, bool glossy, out vec4 radiance) {
  vec4 weights;
  return probeIrradianceWeights(p, n, v, r, glossy, radiance, weights);
}

// The probes' radiance toward d, sky or geometry alike, with the weights probeIrradiance gives
// p, n and v: its cosine-weighted mean over the hemisphere is their irradiance over pi. As
// probeIrradiance: the usable probes' answer and (alpha) its trust, the caller mixing the
// environment's in for the rest (0: no answer). A probe's validity is one texel of
// its irradiance tile (the same in all of them), not a filtered lookup: a software rasterizer
// pays four texels for one of those.
vec4 probeRadianceToward(vec3 p, vec3 n, vec3 v, vec3 d) {
  ivec3 cells[4];
  float tri[4];
  vec3 q = probeTetrahedron(p, n, v, cells, tri);
  vec2 octD = octEncode(d);
  vec2 atlasSize = vec2(textureSize(uProbeAtlas, 0));
  ivec2 irrOrigin = ivec2(probeIrradianceOrigin());
  vec3 sum = vec3(0.0);
  float weightSum = 0.0;
  float coverage = 0.0;
  const int irrTile = PN_PROBE_IRRADIANCE_TEXELS + 2;
  for (int i = 0; i < 4; ++i) {
    vec2 tile = probeTile(cells[i]);
    ivec2 corner = irrOrigin + ivec2(tile) * irrTile;
    if (texelFetch(uProbeAtlas, corner + 1, 0).a > 0.5) {
      float w = probeVisibility(cells[i], tile, p, q, n, atlasSize) * tri[i];
      vec4 rad = textureLod(uProbeAtlas,
                            probeAtlasUv(tile, octD, float(PN_PROBE_RADIANCE_TEXELS), vec2(0.0),
                                         atlasSize),
                            0.0);
      sum += w * rad.rgb;
      weightSum += w;
      coverage += tri[i];
    }
  }
  return weightSum > 0.0 ? vec4(sum / weightSum, probeTrust(coverage)) : vec4(0.0);
}

// The same radiance toward d, in expectation, with the weights a probeIrradianceWeights lookup
// made nearby (the per-view cache's: w0, w1, w2, and w3 = total - the others): one probe drawn
// with probability its weight (u uniform in [0, 1)), its nearest radiance texel. One texel and
// no visibility tests instead of four bilinear lookups of each: a software rasterizer loads
// every texel lane by lane, and those loads were most of the occlusion pass's cost. The mean
// over frames is the same. Alpha: the total (1), or 0 where no probe answered or the drawn one
// is not usable (the caller then takes the environment's radiance: it stands for that probe).
vec4 probeRadianceDrawn(vec3 p, vec3 n, vec3 v, vec3 d, vec3 w, float total, float u) {
  ivec3 cells[4];
  float tri[4];
  probeTetrahedron(p, n, v, cells, tri);
  float x = u * total;
  int pick = x < w.x ? 0 : x < w.x + w.y ? 1 : x < w.x + w.y + w.z ? 2 : 3;
  const int interior = PN_PROBE_RADIANCE_TEXELS;
  ivec2 tile = ivec2(probeTile(cells[pick]));
  ivec2 corner = ivec2(probeIrradianceOrigin()) + tile * (PN_PROBE_IRRADIANCE_TEXELS + 2);
  if (texelFetch(uProbeAtlas, corner + 1, 0).a <= 0.5) return vec4(0.0);
  ivec2 texel = tile * (interior + 2) + 1 +
                clamp(ivec2((octEncode(d) * 0.5 + 0.5) * float(interior)), ivec2(0),
                      ivec2(interior - 1));
  return vec4(texelFetch(uProbeAtlas, texel, 0).rgb, total);
}
