// The punctual-light term of lighting.frag (PN_PUNCTUAL): KHR_lights_punctual samples (spot
// and directional ones shadowed, point lights by their cube maps) and the sky-shadow samples.
// The batch's PN_PUNCTUAL_COUNT samples; the loop over them unrolls (constant indices).
// A sample's kind (uPunctualPos.w, PN_SAMPLE_*: scene/light_kinds.h PunctualSample) says what
// its other uniforms hold; no value of theirs stands for a kind.
uniform vec4 uPunctualPos[MAX_PUNCTUAL];    // xyz, w: PN_SAMPLE_POINT, _SPOT, ... _SKY_SHADOW
uniform vec4 uPunctualDir[MAX_PUNCTUAL];    // xyz direction of travel, w: range (0 = none)
uniform vec3 uPunctualColor[MAX_PUNCTUAL];  // colour * intensity * weight
uniform vec2 uPunctualCone[MAX_PUNCTUAL];   // spot: scale, offset (KHR_lights_punctual)
uniform int uPunctualShadow[MAX_PUNCTUAL];  // point: its cube map, others: their 2D map; -1 none
uniform vec4 uPunctualDisk[MAX_PUNCTUAL];   // sun: xyz centre direction of travel,
                                            // w tan(angular radius); 0 for the others

// The specular lobe of a punctual sample: only the forms this batch's kinds need.
vec3 punctualLobe(vec3 n, vec3 v, vec3 l, vec3 f0, float f90, float alpha, vec4 disk) {
#if (PN_PUNCTUAL_KINDS & PN_KIND_SUN) == 0
  return specularBrdf(n, v, l, f0, f90, alpha, 1.0) * max(dot(n, l), 0.0);
#elif (PN_PUNCTUAL_KINDS & (PN_KIND_POINT | PN_KIND_SPOT | PN_KIND_DIRECTIONAL)) == 0
  return diskSpecular(n, v, f0, f90, alpha, disk);
#else
  return punctualSpecular(n, v, l, f0, f90, alpha, disk);
#endif
}

// Sample i's light at p: the direction toward it (l) and the share that arrives there (the
// inverse square, KHR_lights_punctual's range falloff and a spot's cone; 1 for the distant
// kinds). PN_PUNCTUAL_KINDS (a bit per PN_SAMPLE_*) compiles only the kinds of sample this
// batch has: a software rasterizer would run every kind's code for every light.
float punctualIncidence(int i, int kind, vec3 p, out vec3 l) {
  l = -uPunctualDir[i].xyz;
#if (PN_PUNCTUAL_KINDS & (PN_KIND_POINT | PN_KIND_SPOT)) != 0
  if (kind == PN_SAMPLE_POINT || kind == PN_SAMPLE_SPOT) {
    vec3 toLight = uPunctualPos[i].xyz - p;
    float d2 = max(dot(toLight, toLight), 1e-8);
    l = toLight * inversesqrt(d2);
    float attenuation = 1.0 / d2;
    float range = uPunctualDir[i].w;
    if (range > 0.0) {
      float x = d2 / (range * range);
      attenuation *= saturate(1.0 - x * x);
    }
#if (PN_PUNCTUAL_KINDS & PN_KIND_SPOT) != 0
    if (kind == PN_SAMPLE_SPOT) {
      float a = saturate(dot(uPunctualDir[i].xyz, -l) * uPunctualCone[i].x + uPunctualCone[i].y);
      attenuation *= a * a;
    }
#endif
    return attenuation;
  }
#endif
  return 1.0;
}

// Sample i's shadow at p: a point sample's cube map (only in the batches that have them: the
// two cube lookups would run for every shadow test otherwise), any other's 2D map.
float punctualVisibility(int i, int kind, vec3 p, vec3 normal) {
#if PN_POINT_SHADOWS
  if (kind == PN_SAMPLE_POINT) {
    return uPunctualShadow[i] >= 0 ? pointShadowVisibility(uPunctualShadow[i], p, normal) : 1.0;
  }
#endif
  return shadowVisibility(uPunctualShadow[i], p, normal);
}

// Punctual lights (KHR_lights_punctual): spot and directional samples with a shadow map each
// (directional ones from a direction jittered over the light's angular size), point lights by
// their cube maps; and the sky-shadow samples, which correct the unoccluded diffuse environment
// term while skyLossWeight says it stands.
vec3 punctualTerm(Layers L, float occlusion, float skyLossWeight) {
  vec3 color = vec3(0.0);
  vec3 n = L.n;
  for (int i = 0; i < PN_PUNCTUAL_COUNT; ++i) {
    int kind = int(uPunctualPos[i].w);
    vec3 l;
    float attenuation = punctualIncidence(i, kind, vWorldPos, l);
#if (PN_PUNCTUAL_KINDS & PN_KIND_SKY_SHADOW) != 0
    if (kind == PN_SAMPLE_SKY_SHADOW) {
      // Sky-shadow sample: its colour is radiance / pdf of a direction drawn by the sky's
      // luminance, so colour (n.l) is an unbiased estimate of the environment's irradiance
      // and colour (n.l) (V - 1) of what the shadow takes from the diffuse term.
      float NoLs = dot(n, l);
      if (NoLs <= 0.0 || skyLossWeight <= 0.0) continue;
      float vis = punctualVisibility(i, kind, vWorldPos, normalize(vNormal));
      color += uPunctualColor[i] * ((vis - 1.0) * NoLs * INV_PI * skyLossWeight * occlusion *
                                    L.baseScale * L.sheenScale) *
               L.diffuseColor;
      continue;
    }
#endif
#if (PN_PUNCTUAL_KINDS & ~PN_KIND_SKY_SHADOW) == 0
    continue;  // sky-shadow samples only
#endif
    float NoL = dot(n, l);
#if !PN_DIFFUSE_TRANSMISSION
    // (With diffuse transmission, light from behind passes through: no early out.)
    if (NoL <= 0.0 && (L.coat <= 0.0 || dot(L.coatN, l) <= 0.0)) continue;
#endif
    attenuation *= punctualVisibility(i, kind, vWorldPos, shadowNormal(l));
    vec3 e = uPunctualColor[i] * attenuation;
    vec3 base = L.diffuseColor * (max(NoL, 0.0) * INV_PI) +
                punctualLobe(n, L.v, l, L.f0, L.f90, L.alpha, uPunctualDisk[i]) * L.energyComp;
#if PN_DIFFUSE_TRANSMISSION
    base += L.backColor * (max(-NoL, 0.0) * INV_PI);
#endif
    if (L.sheenMax > 0.0) {
      base = L.sheenScale * base + L.sheenColor * sheenBrdfCos(n, L.v, l, L.sheenA);
    }
    color += e * L.baseScale * base;
    if (L.coat > 0.0) {
#if PN_ANISOTROPY
      bool anisotropic = gAnisotropic;
      gAnisotropic = false;  // the coat's lobe is isotropic
#endif
      color += e * L.coat *
               punctualLobe(L.coatN, L.v, l, vec3(0.04), 1.0, L.coatAlpha, uPunctualDisk[i]);
#if PN_ANISOTROPY
      gAnisotropic = anisotropic;
#endif
    }
  }
  return color;
}
