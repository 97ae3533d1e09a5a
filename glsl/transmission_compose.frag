// KHR_materials_transmission, composed (PN_TRANSMISSION 2): the nearest transmissive layer
// replaces the pixel with its own light (all layers', drawn beside the frame by lighting.frag
// with PN_TRANSMISSION 1) plus what it transmits of the frame's copy behind it
// (chunks/transmission.glsl), under the coat and the sheen like the base.
#include "chunks/lighting_common.glsl"
#include "chunks/transmission.glsl"

out vec4 fragColor;

void main() {
  vec3 v = viewDirection();
  SurfaceInputs s = readSurface(v);
  if (PN_UNLIT != 0 && uUnlit != 0) {
    fragColor = vec4(s.baseColor.rgb * uEnvWeight,
                     uEnvWeight * (uAlphaMode == 2 && uCoverageFrame < 0 ? s.baseColor.a : 1.0));
    return;
  }
  Layers L = surfaceLayers(s, v);
  // A smooth surface (at the shading's roughness floor) transmits without scattering: GGX's
  // long tail at that floor would still throw a few samples pixels away.
  float transmitAlpha = s.perceptualRoughness > MIN_PERCEPTUAL_ROUGHNESS ? L.alpha : 0.0;
  vec3 own = texelFetch(uGlassLight, ivec2(gl_FragCoord.xy), 0).rgb;
  fragColor = vec4(own + L.baseScale * L.sheenScale * L.transmitColor *
                             transmittedRadiance(vWorldPos, L.n, v, transmitAlpha, uIor),
                   1.0);
}
