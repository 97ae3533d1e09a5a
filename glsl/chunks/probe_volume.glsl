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

// The atlas position of direction `oct` (octEncode's) in a probe's tile of the map whose tiles
// have `interior` texels inside a one-texel border and start at `origin`.
vec2 probeAtlasUv(int probe, vec2 oct, float interior, vec2 origin, vec2 atlasSize) {
  float tile = interior + 2.0;
  vec2 corner = origin + vec2(float(probe % uProbeColumns), float(probe / uProbeColumns)) * tile;
  return (corner + 1.0 + (oct * 0.5 + 0.5) * interior) / atlasSize;
}

// Irradiance at p for normal n, seen from direction v (unit, toward the viewer), and the
// summed weight of the captured probes it comes from (0: none yet, use something else). Outside
// captures, and with `glossy`, also the probes' radiance toward r (rgb) and the share of it that
// is geometry (a).
vec4 probeIrradiance(vec3 p, vec3 n, vec3 v, vec3 r, bool glossy, out vec4 radiance) {
  // n and r are the same for every probe: encode them once.
  vec2 octN = octEncode(n);
  vec2 octR = octEncode(r);
  vec2 atlasSize = vec2(textureSize(uProbeAtlas, 0));
  const float radianceTile = float(PN_PROBE_RADIANCE_TEXELS + 2);
  vec2 depthOrigin = vec2(float(uProbeColumns) * radianceTile, 0.0);
  vec2 irrOrigin = depthOrigin + vec2(0.0, float(uProbeRows * (PN_PROBE_DEPTH_TEXELS + 2)));
  vec4 radSum = vec4(0.0);
  float minSpacing = min(uProbeSpacing.x, min(uProbeSpacing.y, uProbeSpacing.z));
  // Off the surface, mostly toward the viewer: the lookup must not start inside the wall.
  vec3 q = p + (0.2 * n + 0.15 * v) * minSpacing;
  vec3 g = (q - uProbeOrigin) / uProbeSpacing;
  ivec3 counts = ivec3(uProbeCounts + 0.5);
  ivec3 last = counts - 1;
  ivec3 base = clamp(ivec3(floor(g)), ivec3(0), max(last - 1, ivec3(0)));
  vec3 f = clamp(g - vec3(base), 0.0, 1.0);
  vec3 sum = vec3(0.0);
  float weightSum = 0.0;
  float coverage = 0.0;
  // Four probes, not eight: the cube is split into six tetrahedra along its main diagonal
  // (Kuhn), and the point's barycentric weights in its own tetrahedron interpolate linearly
  // and continuously. Half the texture fetches of trilinear weights, which a software
  // rasterizer pays for at every pixel.
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
  for (int i = 0; i < 4; ++i) {
    ivec3 o = i == 0 ? ivec3(0) : i == 1 ? ea : i == 2 ? ea + eb : ivec3(1);
    ivec3 c = min(base + o, last);
    float tri = i == 0 ? 1.0 - fa : i == 1 ? fa - fb : i == 2 ? fb - fc : fc;
    int index = c.x + counts.x * (c.y + counts.y * c.z);
    vec3 probePos = uProbeOrigin + vec3(c) * uProbeSpacing;
    vec3 toProbe = probePos - p;
    float back = (dot(normalize(toProbe), n) + 1.0) * 0.5;
    float w = back * back + 0.05;
    vec3 fromProbe = q - probePos;
    float dist = length(fromProbe);
    vec2 m = texture(uProbeAtlas,
                     probeAtlasUv(index, octEncode(dist > 0.0 ? fromProbe / dist : n),
                                  float(PN_PROBE_DEPTH_TEXELS), depthOrigin, atlasSize)).rg;
    float d = dist / uProbeDiagonal;
    if (d > m.x) {
      float variance = abs(m.y - m.x * m.x);
      float e = d - m.x;
      float chebyshev = variance / (variance + e * e);
      w *= chebyshev * chebyshev * chebyshev;
    }
    w = max(w, 1e-5);
    // Crush small weights: a barely visible probe should not tint the result.
    if (w < 0.2) w *= w * w * 25.0;
    vec4 irr = texture(uProbeAtlas, probeAtlasUv(index, octN, float(PN_PROBE_IRRADIANCE_TEXELS),
                                                 irrOrigin, atlasSize));
    float valid = irr.a > 0.5 ? 1.0 : 0.0;
    w *= tri * valid;
    coverage += tri * valid;
    sum += w * irr.rgb;
    weightSum += w;
#if !PN_CAPTURE
    if (glossy) {
      vec4 rad = texture(uProbeAtlas, probeAtlasUv(index, octR, float(PN_PROBE_RADIANCE_TEXELS),
                                                   vec2(0.0), atlasSize));
      radSum += (w * rad.a) * vec4(rad.rgb, 1.0);
    }
#endif
  }
  radiance = radSum.a > 0.0 ? vec4(radSum.rgb / radSum.a, radSum.a / weightSum) : vec4(0.0);
  return weightSum > 0.0 ? vec4(sum / weightSum, coverage) : vec4(0.0);
}
