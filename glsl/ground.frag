// The shadow-catching ground (RenderSettings::shadowIntensity; passes/ground_shadow.cpp): a
// white Lambertian plane under the scene, which shows only what the scene takes from its light.
// Each frame it shades itself with the batch's terms both as lit (the environment's irradiance
// with this frame's sky-shadow sample, the punctual lights with their shadows) and unshadowed,
// in luminance, a blocked sky direction lit by the blocker's radiance instead where the probe
// volume is on. The unshadowed light is the same every frame, so the ratio's mean over frames
// is the share of the light the ground keeps. The frame behind it (the background, or nothing with a
// transparent background) is multiplied by 1 - intensity (1 - ratio) (gl::Blend::Multiply),
// and with a transparent background alpha gets intensity (1 - ratio): a shadow over the page. Area lights are not caught (their
// batches do not draw the ground).
#define PN_GROUND 1
#include "chunks/lighting_common.glsl"

uniform float uShadowIntensity;
uniform vec3 uGroundCenter;  // as ground.vert's
uniform float uGroundHalf;
uniform float uTransparent;  // 1: the darkening is also the pixel's alpha (coverage)

out vec4 fragColor;

#if PN_PUNCTUAL
// The punctual samples' light on the ground (normal up, white, Lambertian), with
// chunks/punctual_term.glsl's incidence and shadows, lit and unshadowed in one pass over them.
// A sky-shadow sample changes only `lit`: the environment's unoccluded term stands in `open`.
void punctualGround(inout float lit, inout float open) {
  vec3 n = vec3(0.0, 1.0, 0.0);
  for (int i = 0; i < PN_PUNCTUAL_COUNT; ++i) {
    int kind = int(uPunctualPos[i].w);
    vec3 l;
    float attenuation = punctualIncidence(i, kind, vWorldPos, l);
    float NoL = dot(n, l);
    if (NoL <= 0.0) continue;
    float e = luminance(uPunctualColor[i]) * attenuation * NoL * INV_PI;
    float visibility = punctualVisibility(i, kind, vWorldPos, n);
    if (kind == PN_SAMPLE_SKY_SHADOW) {
      // Its colour is the sky's radiance over its density: what the blocker takes away.
      float lost = e * (1.0 - visibility);
#if PN_PROBES
      // A catcher receives the blocker's light instead (Cycles' does: a white sphere's shadow
      // is half as dark as a black one's), in the ratio of their radiances in that direction:
      // the probes' radiance of the geometry they see toward it. The probes do not see the
      // ground, so light it sends back up and receives again is left out.
      // (Only where it is blocked: most of the ground is not, and skips the probes' lookups.)
      if (visibility < 1.0) {
        float sky = luminance(envRadiance(l, 0.0));
        vec4 blocker = probeGeometryToward(vWorldPos, n, viewDirection(), l);
        // At most the sky's own light: a body lit by this environment (without a ground)
        // sends less toward the ground than the sky it hides, and a dim sky direction's ratio
        // would otherwise be a firefly.
        if (sky > 0.0) lost *= 1.0 - blocker.a * min(luminance(blocker.rgb) / sky, 1.0);
      }
#endif
      lit -= lost;
    } else {
      lit += e * visibility;
      open += e;
    }
  }
}
#endif

void main() {
  // The square's corners, past the fade: nothing to darken (a fifth of its area).
  float r = length(vWorldPos.xz - uGroundCenter.xz) / uGroundHalf;
  if (r >= 1.0) discard;
  float open = luminance(envIrradiance(vec3(0.0, 1.0, 0.0))) * INV_PI, lit = open;
#if PN_PUNCTUAL
  punctualGround(lit, open);
#endif
  // Not clamped: a sky-shadow sample's correction is an estimate, below -1 or above 0 in single
  // frames (its colour is the sky's radiance over its density); the mean is the share.
  float visible = open > 0.0 ? lit / open : 1.0;
  // The square is finite: its darkening fades out over its outer half (at its edge, 1.5 times
  // the scene's size away, a body of that size takes a few per cent of a uniform sky's light).
  float darkening = uShadowIntensity * (1.0 - visible) * (1.0 - smoothstep(0.5, 1.0, r));
  fragColor = vec4(vec3(1.0 - darkening), darkening * uTransparent);
}
