// The environment behind the scene, optionally blurred by sampling a rougher prefiltered mip.
#include "chunks/environment.glsl"
uniform mat4 uInvViewProj;
uniform float uBackgroundBlur;  // perceptual roughness of the mip shown
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
void main() {
  vec4 far = uInvViewProj * vec4(vUv * 2.0 - 1.0, 0.0, 1.0);  // z = 0: finite with an infinite far plane
  vec4 near = uInvViewProj * vec4(vUv * 2.0 - 1.0, -1.0, 1.0);
  vec3 dir = normalize(far.xyz / far.w - near.xyz / near.w);
  fragColor = vec4(envRadiance(dir, uBackgroundBlur), uBackgroundAlpha);
#if PN_ACCUMULATE
  fragColor.rgb *= uBackgroundScale;
  fragColor = runningMean(texelFetch(uPrevious, ivec2(gl_FragCoord.xy), 0), fragColor);
#endif
}
