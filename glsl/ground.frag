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

#if PN_PROBES
// The radiance of the geometry the probes around p see toward d (chunks/probe_volume.glsl's
// maps; the ground's blocker): each radiance texel's sky share (1 - alpha, at the environment's
// radiance) taken out, the four probes weighted by their barycentric weights and how much
// geometry they see there (no visibility tests: the blocker's light is smooth, and the ground
// pays for every lookup); alpha: the weight of geometry found (0: none, no answer).
vec4 probeGeometryToward(vec3 p, vec3 n, vec3 v, vec3 d) {
  ivec3 cells[4];
  float tri[4];
  probeTetrahedron(p, n, v, cells, tri);
  vec2 octD = octEncode(d);
  vec2 atlasSize = vec2(textureSize(uProbeAtlas, 0));
  ivec2 irrOrigin = ivec2(probeIrradianceOrigin());
  vec3 sky = envRadiance(d, 0.0);
  vec3 sum = vec3(0.0);
  float weightSum = 0.0;
  const int irrTile = PN_PROBE_IRRADIANCE_TEXELS + 2;
  for (int i = 0; i < 4; ++i) {
    vec2 tile = probeTile(cells[i]);
    if (texelFetch(uProbeAtlas, irrOrigin + ivec2(tile) * irrTile + 1, 0).a > 0.5) {
      vec4 rad = textureLod(uProbeAtlas,
                            probeAtlasUv(tile, octD, float(PN_PROBE_RADIANCE_TEXELS), vec2(0.0),
                                         atlasSize),
                            0.0);
      sum += tri[i] * max(rad.rgb - (1.0 - rad.a) * sky, vec3(0.0));
      weightSum += tri[i] * rad.a;
    }
  }
  return weightSum > 0.0 ? vec4(sum / weightSum, 1.0) : vec4(0.0);
}
#endif

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
