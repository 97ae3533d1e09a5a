// Probe volume (passes/probe_volume.h): irradiance probes on a grid over the scene, each with
// an octahedral map of irradiance (alpha: 1 once captured and not buried in geometry) and one
// of the mean and mean square distance to what it sees (in units of the volume's diagonal).
// A shading point blends its eight surrounding probes: trilinear weights, times a soft
// backface weight (probes behind the surface count less), times Chebyshev's bound on the
// probability that the probe sees the point (no light through walls), as in DDGI (Majercik et
// al., JCGT 2019) and Eevee's irradiance grid.
#include "chunks/octahedral.glsl"

uniform int uProbeEnabled;
uniform vec3 uProbeOrigin;
uniform vec3 uProbeSpacing;
uniform vec3 uProbeCounts;  // whole numbers
uniform float uProbeDiagonal;
uniform int uProbeColumns;
uniform sampler2D uProbeIrradiance;
uniform sampler2D uProbeDepth;

vec2 probeAtlasUv(int probe, vec3 dir, float interior, vec2 atlasSize) {
  float tile = interior + 2.0;
  vec2 corner = vec2(float(probe % uProbeColumns), float(probe / uProbeColumns)) * tile;
  return (corner + 1.0 + (octEncode(dir) * 0.5 + 0.5) * interior) / atlasSize;
}

// Irradiance at p for normal n, seen from direction v (unit, toward the viewer), and the
// summed weight of the captured probes it comes from (0: none yet, use something else).
vec4 probeIrradiance(vec3 p, vec3 n, vec3 v) {
  vec2 irrSize = vec2(textureSize(uProbeIrradiance, 0));
  vec2 depthSize = vec2(textureSize(uProbeDepth, 0));
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
  for (int i = 0; i < 8; ++i) {
    ivec3 o = ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    ivec3 c = min(base + o, last);
    vec3 tri3 = mix(1.0 - f, f, vec3(o));
    float tri = tri3.x * tri3.y * tri3.z;
    int index = c.x + counts.x * (c.y + counts.y * c.z);
    vec3 probePos = uProbeOrigin + vec3(c) * uProbeSpacing;
    vec3 toProbe = probePos - p;
    float back = (dot(normalize(toProbe), n) + 1.0) * 0.5;
    float w = back * back + 0.05;
    vec3 fromProbe = q - probePos;
    float dist = length(fromProbe);
    vec2 m = texture(uProbeDepth,
                     probeAtlasUv(index, dist > 0.0 ? fromProbe / dist : n, float(PN_PROBE_DEPTH_TEXELS), depthSize)).rg;
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
    vec4 irr = texture(uProbeIrradiance,
                       probeAtlasUv(index, n, float(PN_PROBE_IRRADIANCE_TEXELS), irrSize));
    float valid = irr.a > 0.5 ? 1.0 : 0.0;
    w *= tri * valid;
    coverage += tri * valid;
    sum += w * irr.rgb;
    weightSum += w;
  }
  return weightSum > 0.0 ? vec4(sum / weightSum, coverage) : vec4(0.0);
}
