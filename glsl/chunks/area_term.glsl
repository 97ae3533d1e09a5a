// The area-light term of lighting.frag (PN_AREA): this batch's light samples, each shadowed by
// its own shadow map, with the light's unshadowed shading (Karis' representative point,
// chunks/area_lights.glsl) computed once per light or read from the per-view light cache.
//
// The batch's samples: PN_AREA_COUNT of them, sorted by light (bit i of PN_AREA_STARTS: sample
// i's light is not sample i - 1's). Loops over them run to that constant and unroll, so arrays
// are read at constant indices.
uniform vec3 uAreaPos[MAX_AREA];
uniform vec3 uAreaDir[MAX_AREA];
uniform vec3 uAreaRight[MAX_AREA];
uniform vec3 uAreaUp[MAX_AREA];
uniform vec4 uAreaShape[MAX_AREA];     // width, height, shape (PN_LIGHT_*), shadow map (-1 none)
uniform vec3 uAreaRadiance[MAX_AREA];  // colour * luminance * sample weight

#if PN_LIGHT_CACHE
// The area lights' per-view cache: a light's unshadowed shading, the mean over the view's
// first jittered frames, so only the samples' shadow tests remain per frame. Its mean over the
// pixel stands in for the shading at this frame's sub-pixel position: exact wherever the
// pixel's samples agree on visibility, a ratio estimate (Heitz et al. 2018) at silhouettes.
uniform highp sampler2DArray uLightCache;
uniform int uAreaLayer[MAX_AREA];  // the cache layer of each sample's light
#endif

AreaLight areaLightOf(int i) {
  AreaLight A;
  A.position = uAreaPos[i];
  A.direction = uAreaDir[i];
  A.right = uAreaRight[i];
  A.up = uAreaUp[i];
  A.size = uAreaShape[i].xy;
  A.shape = int(uAreaShape[i].z + 0.5);
  return A;
}

// Light A's unshadowed shading at the pixel per unit radiance: what each of its samples
// multiplies by its shadow-map visibility.
vec3 areaShading(AreaLight A, Layers L) {
  float irradiance;
  vec3 specular;
  evaluateAreaLight(A, vWorldPos, L.n, L.v, L.f0, L.f90, L.alpha, irradiance, specular);
  // Sheen: its lobe is broad, so the light's irradiance times the lobe's value D V toward the
  // light's centre (irradiance already holds the cosine).
  float sheenLight = 0.0;
  if (L.sheenMax > 0.0 && irradiance > 0.0) {
    vec3 lc = normalize(A.position - vWorldPos);
    float NoLc = dot(L.n, lc);
    sheenLight = NoLc > 0.0 ? sheenBrdfCos(L.n, L.v, lc, L.sheenA) / NoLc : 0.0;
  }
  vec3 coatSpecular = vec3(0.0);
  if (L.coat > 0.0) {
    float coatIrradiance;
#if PN_ANISOTROPY
    bool anisotropic = gAnisotropic;
    gAnisotropic = false;  // the coat's lobe is isotropic
#endif
    evaluateAreaLight(A, vWorldPos, L.coatN, L.v, vec3(0.04), 1.0, L.coatAlpha, coatIrradiance,
                      coatSpecular);
#if PN_ANISOTROPY
    gAnisotropic = anisotropic;
#endif
  }
  vec3 back = vec3(0.0);
#if PN_DIFFUSE_TRANSMISSION
  // Diffuse transmission: the light's irradiance on the other side.
  back = L.backColor * (areaLightIrradiance(A, vWorldPos, -L.n) * INV_PI);
#endif
  return L.baseScale * (L.sheenScale * (L.diffuseColor * irradiance * INV_PI +
                                        specular * L.energyComp + back) +
                        L.sheenColor * (sheenLight * irradiance)) +
         L.coat * coatSpecular;
}

// The area-light samples, sorted by light: a light's unshadowed shading is the same for all of
// its samples, so it is computed once (or read from the per-view cache) and only the
// shadow-map visibility differs.
vec3 areaTerm(Layers L) {
  vec3 color = vec3(0.0);
  vec3 shaded = vec3(0.0);
  for (int i = 0; i < PN_AREA_COUNT; ++i) {
#if PN_LIGHT_CACHE
    // The mean over the positions that saw a surface: at a silhouette against the sky the
    // others added nothing, and this sample is on the surface.
    vec4 cached = texelFetch(uLightCache, ivec3(ivec2(gl_FragCoord.xy), uAreaLayer[i]), 0);
    shaded = cached.rgb / max(cached.a, 1e-3);
#else
    if ((PN_AREA_STARTS & (1 << i)) != 0) shaded = areaShading(areaLightOf(i), L);
#endif
    float visibility =
        shadowVisibility(int(uAreaShape[i].w), vWorldPos, shadowNormal(uAreaPos[i] - vWorldPos));
    color += uAreaRadiance[i] * visibility * shaded;
  }
  return color;
}
