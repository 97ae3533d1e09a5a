// This frame's diffuse rays (occlusion_trace.frag's output, a texel a 2x2 block) averaged with
// their neighbours' on the same surface (passes/occlusion_pass.h): one ray a pixel made frames
// 2-8 grainier than frame 1, whose environment light is smooth (issue #59). The neighbours'
// weight, uStrength, is 1 in frame 2 and fades to 0 (progressive/distributor.h,
// rayFilterWeight), so the mean converges to the unfiltered estimate; the average of zero-mean
// corrections keeps the mean (a miss's zero is averaged in like any other sample).
// Neighbours count where their linear depth lies within a few per cent per block of the
// centre's and their normals agree (a corner's two walls get different light).
uniform sampler2D uRays;     // rgb: the correction, a: +-linear depth (+ blocked), 0 background
uniform sampler2D uPrepass;  // full resolution: xyz view normal, w linear depth
uniform int uBlock;
uniform float uStrength;
// Separable: along rows (0), then along the first pass's result down columns (1), five blocks
// each: the 5x5 neighbourhood for 20 fetches a pixel where one 5x5 pass took 50 (and 25 ms a
// frame at 1280x720 on a software rasterizer).
uniform int uVertical;
out vec4 fragColor;

const int RADIUS = 2;

vec3 blockNormal(ivec2 b) {
  ivec2 size = textureSize(uPrepass, 0);
  return texelFetch(uPrepass, min(b * uBlock, size - 1), 0).xyz;
}

void main() {
  ivec2 c = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(uRays, 0);
  ivec2 along = uVertical != 0 ? ivec2(0, 1) : ivec2(1, 0);
  vec4 centre = texelFetch(uRays, c, 0);
  float z = abs(centre.a);
  vec3 n = blockNormal(c);
  vec3 sum = centre.rgb;
  float total = 1.0;
  for (int k = -RADIUS; k <= RADIUS; ++k) {
    if (k == 0) continue;
    ivec2 q = clamp(c + k * along, ivec2(0), size - 1);
    vec4 s = texelFetch(uRays, q, 0);
    float sameDepth = step(abs(abs(s.a) - z), 0.03 * z * float(abs(k))) * step(1e-6, abs(s.a));
    float cosine = saturate(dot(blockNormal(q), n));
    cosine *= cosine;
    cosine *= cosine;
    cosine *= cosine;
    cosine *= cosine;  // ^16: normals within about 20 degrees
    float w = uStrength * sameDepth * cosine;
    sum += w * s.rgb;
    total += w;
  }
  // (The depth in alpha passes through: the second pass tests against it.)
  fragColor = z > 0.0 ? vec4(sum / total, centre.a) : centre;
}
