// Forward shading of one intermediate frame: split-sum environment light (with this frame's
// occlusion sample once the prepass exists), this frame's area-light samples (each weighted by
// the sample distributor and shadowed by its own shadow map), punctual lights and emission.
// The variants and the terms: chunks/lighting_common.glsl. Frame 1 (environment only) runs a
// plain forward pass; with PN_ACCUMULATE the frame's only batch adds its sample straight to the
// running mean (chunks/accumulate.glsl), drawn into the other accumulation target. With
// PN_TRANSMISSION 1 it is a transmissive surface's own light, which transmission_compose.frag
// composes with what the surface transmits.
#include "chunks/lighting_common.glsl"
#if PN_ACCUMULATE
#include "chunks/accumulate.glsl"
uniform sampler2D uPrevious;  // the mean so far (the same texture as uAccumulated)
#endif

out vec4 fragColor;

// The frame's sample at this pixel: the surface's layers, then each term and the emission.
void shade() {
  vec3 v = viewDirection();
  SurfaceInputs s = readSurface(v);
  if (PN_UNLIT != 0 && uUnlit != 0) {
    // KHR_materials_unlit: the base colour is the radiance (once, in the first batch).
    fragColor = vec4(s.baseColor.rgb * uEnvWeight,
                     uEnvWeight * (uAlphaMode == 2 && uCoverageFrame < 0 ? s.baseColor.a : 1.0));
    return;
  }
  Layers L = surfaceLayers(s, v);
  vec3 color = surfaceLight(L, s.occlusion) + s.emissive * uEnvWeight;
  // Alpha marks what screen-space indirect light may reuse: an area light's visible face is
  // excluded (its light is already counted by the analytic area light; uLampFaceAlpha), and
  // extra light batches add nothing. Alpha-blended BLEND surfaces (frame 1) put their coverage
  // there for the blend instead.
  float reusable =
      uIndirectEmission > 0.5 || max(s.emissive.r, max(s.emissive.g, s.emissive.b)) <= 0.0
          ? 1.0
          : uLampFaceAlpha;
  bool blended = uAlphaMode == 2 && uCoverageFrame < 0;
  fragColor = vec4(color, uEnvWeight * (blended ? s.baseColor.a : reusable));
}

void main() {
#if PN_OCCLUSION
  setSampleKeys();  // derivatives, before any early return
#endif
  shade();
#if PN_ACCUMULATE
  fragColor = runningMean(texelFetch(uPrevious, ivec2(gl_FragCoord.xy), 0), fragColor);
#endif
}
