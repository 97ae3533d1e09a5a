// Bloom (passes/effects/bloom.cpp), one stage per program (PN_BLOOM_STAGE):
//  0: the first, half-size level from the radiance: the mean of the 2x2 texels under the pixel
//     (texelFetch: the accumulation format need not be filterable), each weighted by
//     1 / (1 + luma) (Karis), so that a single firefly does not bloom;
//  1: the next level down: the 13-tap filter of Jimenez (Next Generation Post Processing in
//     Call of Duty: Advanced Warfare, 2014), bilinear taps;
//  2: up: a 3x3 tent of the smaller level, added (blending) to the level above;
//  3: composite: mix(radiance, bloom / levels, strength). Every level is an energy-conserving
//     blur and the sum of `levels` of them is divided by their number, so the image's mean
//     radiance is kept: light is moved, not added.
uniform sampler2D uSource;
uniform sampler2D uBloom;
uniform vec2 uTexel;  // 1 / the source's size
uniform float uStrength;
uniform float uLevels;
in vec2 vUv;
out vec4 fragColor;

vec3 tap(vec2 offset) {
  return texture(uSource, vUv + offset * uTexel).rgb;
}

void main() {
#if PN_BLOOM_STAGE == 0
  ivec2 size = textureSize(uSource, 0);
  ivec2 base = ivec2(gl_FragCoord.xy) * 2;
  vec3 sum = vec3(0.0);
  float weights = 0.0;
  for (int i = 0; i < 4; ++i) {
    ivec2 p = min(base + ivec2(i & 1, i >> 1), size - 1);
    vec3 c = max(texelFetch(uSource, p, 0).rgb, vec3(0.0));
    // Non-finite samples never reach the mean; a huge one is tamed by the weight.
    float w = 1.0 / (1.0 + luminance(c));
    sum += c * w;
    weights += w;
  }
  fragColor = vec4(sum / weights, 1.0);
#elif PN_BLOOM_STAGE == 1
  vec3 a = tap(vec2(-2.0, 2.0)), b = tap(vec2(0.0, 2.0)), c = tap(vec2(2.0, 2.0));
  vec3 d = tap(vec2(-2.0, 0.0)), e = tap(vec2(0.0)), f = tap(vec2(2.0, 0.0));
  vec3 g = tap(vec2(-2.0, -2.0)), h = tap(vec2(0.0, -2.0)), i = tap(vec2(2.0, -2.0));
  vec3 j = tap(vec2(-1.0, 1.0)), k = tap(vec2(1.0, 1.0));
  vec3 l = tap(vec2(-1.0, -1.0)), m = tap(vec2(1.0, -1.0));
  vec3 down = e * 0.125 + (a + c + g + i) * 0.03125 + (b + d + f + h) * 0.0625 +
              (j + k + l + m) * 0.125;
  fragColor = vec4(down, 1.0);
#elif PN_BLOOM_STAGE == 2
  vec3 up = tap(vec2(0.0)) * 4.0;
  up += (tap(vec2(-1.0, 0.0)) + tap(vec2(1.0, 0.0)) + tap(vec2(0.0, -1.0)) + tap(vec2(0.0, 1.0))) *
        2.0;
  up += tap(vec2(-1.0, -1.0)) + tap(vec2(1.0, -1.0)) + tap(vec2(-1.0, 1.0)) + tap(vec2(1.0, 1.0));
  fragColor = vec4(up / 16.0, 1.0);
#else
  vec4 source = texelFetch(uSource, ivec2(gl_FragCoord.xy), 0);
  vec3 bloom = texture(uBloom, vUv).rgb / uLevels;
  // Alpha passes through: the scene's coverage with a transparent background.
  fragColor = vec4(mix(source.rgb, bloom, uStrength), source.a);
#endif
}
