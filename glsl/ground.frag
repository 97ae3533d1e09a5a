// The shadow-catching ground (RenderSettings::shadowIntensity; passes/ground_shadow.cpp): a
// white Lambertian plane under the scene, which shows only what the scene takes from its light.
// Each frame it shades itself twice with the batch's terms (chunks/lighting_common.glsl): as
// lit, the environment's irradiance with this frame's sky-shadow sample and the punctual lights
// with their shadows; and unshadowed (gUnshadowed). The environment's share is the same both
// times, so the ratio's mean over frames is the visible share of the light. The frame behind
// it (the background, or nothing with a transparent background) is multiplied by
// 1 - intensity (1 - ratio) (gl::Blend::Multiply), and with a transparent background alpha
// gets intensity (1 - ratio): a shadow over the page. Area lights are not caught (their
// batches do not draw the ground).
#define PN_GROUND 1
#include "chunks/lighting_common.glsl"

uniform float uShadowIntensity;
uniform vec3 uGroundCenter;  // as ground.vert's
uniform float uGroundHalf;
uniform float uTransparent;  // 1: the darkening is also the pixel's alpha (coverage)

out vec4 fragColor;

// A white Lambertian surface: no specular lobe, no coat, no sheen.
Layers whiteLambert(vec3 n, vec3 v) {
  Layers L;
  L.n = n;
  L.v = v;
  L.NoV = max(dot(n, v), 1e-4);
  L.diffuseColor = vec3(1.0);
  L.f0 = vec3(0.0);
  L.f90 = 0.0;
  L.perceptualRoughness = 1.0;
  L.alpha = 1.0;
  L.specularScale = vec3(0.0);
  L.energyComp = vec3(0.0);
  L.coat = 0.0;
  L.coatN = n;
  L.coatNoV = L.NoV;
  L.coatRoughness = 1.0;
  L.coatAlpha = 1.0;
  L.baseScale = 1.0;
  L.sheenColor = vec3(0.0);
  L.sheenMax = 0.0;
  L.sheenA = 1.0;
  L.sheenE = 0.0;
  L.sheenScale = 1.0;
  L.transmitColor = vec3(0.0);
  L.backColor = vec3(0.0);
  return L;
}

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

void main() {
  Layers L = whiteLambert(vec3(0.0, 1.0, 0.0), viewDirection());
  vec3 unoccluded = envIrradiance(L.n) * INV_PI;
  vec3 lit = unoccluded, open = unoccluded;
#if PN_PUNCTUAL
  lit += punctualTerm(L, 1.0, 1.0);
  gUnshadowed = true;
  open += punctualTerm(L, 1.0, 1.0);
#endif
  // Not clamped: a sky-shadow sample's correction is an estimate, below -1 or above 0 in single
  // frames (its colour is the sky's radiance over its density); the mean is the share.
  float reference = luminance(open);
  float visible = reference > 0.0 ? luminance(lit) / reference : 1.0;
  // The square is finite: its darkening fades out over its outer half (at its edge, twice the
  // scene's size away, a body of that size takes about 1-2 % of a uniform sky's light).
  float r = length(vWorldPos.xz - uGroundCenter.xz) / uGroundHalf;
  float darkening = uShadowIntensity * (1.0 - visible) * (1.0 - smoothstep(0.5, 1.0, r));
  fragColor = vec4(vec3(1.0 - darkening), darkening * uTransparent);
}
