// The environment behind the scene, optionally blurred by sampling a rougher prefiltered mip.
#include "chunks/environment.glsl"
uniform mat4 uInvViewProj;
uniform float uBackgroundBlur;  // perceptual roughness of the mip shown (PN_BLUR)
uniform float uBackgroundAlpha;  // 1, or a probe capture's distance for the sky
#if PN_ACCUMULATE
// The frame's only batch accumulates as it draws (lighting.frag): so does the background, or
// the clear colour where none is shown (uBackgroundScale 0).
#include "chunks/accumulate.glsl"
uniform sampler2D uPrevious;
uniform float uBackgroundScale;
#endif
in vec2 vUv;
out vec4 fragColor;

#if PN_BLUR
// The environment in world direction `dir` at one mip level, through a cubic B-spline: a
// blurred background magnifies a small mip (a 64-texel face at blur 0.25 shows 32 texels
// across 90 degrees), and bilinear filtering shows its texel grid as kinks, streaks from bright
// corners and blocks. The B-spline is smooth (C2) and costs four bilinear taps placed between
// texel centres by its weights (Sigg and Hadwiger, GPU Gems 2, ch. 20), on the face's grid.
vec3 bsplineLevel(vec3 dir, float level) {
  vec3 d = uEnvRotation * dir;
  vec3 a = abs(d);
  // The face's axis n and the two axes s, t of its texel grid (selects, not branches: a
  // software rasterizer would run every branch).
  bool xMajor = a.x >= a.y && a.x >= a.z, yMajor = !xMajor && a.y >= a.z;
  vec3 n = xMajor ? vec3(sign(d.x), 0.0, 0.0)
                  : (yMajor ? vec3(0.0, sign(d.y), 0.0) : vec3(0.0, 0.0, sign(d.z)));
  vec3 s = xMajor ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  vec3 t = yMajor ? vec3(0.0, 0.0, 1.0) : vec3(0.0, 1.0, 0.0);
  float texels = float(textureSize(uEnvSpecular, int(level)).x);
  vec2 uv = vec2(dot(d, s), dot(d, t)) / dot(d, n);  // [-1, 1] on the face
  vec2 tc = (uv * 0.5 + 0.5) * texels - 0.5;          // texel centres at integers
  vec2 base = floor(tc);
  vec2 f = tc - base, f2 = f * f, f3 = f2 * f;
  vec2 w0 = (1.0 - 3.0 * f + 3.0 * f2 - f3) / 6.0, w1 = (4.0 - 6.0 * f2 + 3.0 * f3) / 6.0;
  vec2 w2 = (1.0 + 3.0 * f + 3.0 * f2 - 3.0 * f3) / 6.0, w3 = f3 / 6.0;
  vec2 g0 = w0 + w1, g1 = w2 + w3;
  // Where one bilinear tap weighs texels base-1 and base (base+1 and base+2) as w0 : w1.
  vec2 p0 = ((base - 1.0 + w1 / g0) + 0.5) / texels * 2.0 - 1.0;
  vec2 p1 = ((base + 1.0 + w3 / g1) + 0.5) / texels * 2.0 - 1.0;
  vec3 r = g0.x * g0.y * textureLod(uEnvSpecular, n + p0.x * s + p0.y * t, level).rgb +
           g1.x * g0.y * textureLod(uEnvSpecular, n + p1.x * s + p0.y * t, level).rgb +
           g0.x * g1.y * textureLod(uEnvSpecular, n + p0.x * s + p1.y * t, level).rgb +
           g1.x * g1.y * textureLod(uEnvSpecular, n + p1.x * s + p1.y * t, level).rgb;
  return r * uEnvIntensity;
}

// The background at perceptual roughness `blur`: between two mips, both filtered.
vec3 filteredRadiance(vec3 dir, float blur) {
  float lod = clamp(blur, 0.0, 1.0) * uEnvMaxMip;
  float level = floor(lod), between = lod - level;
  vec3 r = bsplineLevel(dir, level);
  if (between > 0.0) r = mix(r, bsplineLevel(dir, min(level + 1.0, uEnvMaxMip)), between);
  return r;
}
#else
// Sharp (PN_BLUR 0, a program of its own): one tap, as the environment's own resolution shows
// it. Not a uniform branch: a software GL ran the filter's four to eight taps too, which cost a
// 1280x720 frame on llvmpipe 13 to 28 ms of its lighting (issue #59).
vec3 filteredRadiance(vec3 dir, float blur) {
  return envRadiance(dir, 0.0);
}
#endif

void main() {
  vec4 far = uInvViewProj * vec4(vUv * 2.0 - 1.0, 0.0, 1.0);  // z = 0: finite with an infinite far plane
  vec4 near = uInvViewProj * vec4(vUv * 2.0 - 1.0, -1.0, 1.0);
  vec3 dir = normalize(far.xyz / far.w - near.xyz / near.w);
  fragColor = vec4(filteredRadiance(dir, uBackgroundBlur), uBackgroundAlpha);
#if PN_ACCUMULATE
  fragColor.rgb *= uBackgroundScale;
  fragColor = runningMean(texelFetch(uPrevious, ivec2(gl_FragCoord.xy), 0), fragColor);
#endif
}
