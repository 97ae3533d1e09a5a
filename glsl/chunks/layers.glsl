// The surface's layers (lighting.frag): the metallic-roughness base with its split-sum
// albedo, the clearcoat over it and the sheen between them, computed once per pixel from the
// material's inputs (chunks/material.glsl) and read by every lighting term.
struct Layers {
  vec3 n;  // shading normal, facing the viewer
  vec3 v;  // toward the viewer
  float NoV;
  vec3 diffuseColor;
  vec3 f0;
  float f90;
  float perceptualRoughness;
  float alpha;
  vec3 specularScale;  // the split sum's directional albedo of the specular lobe
  // Multiple scattering (Fdez-Aguera 2019): what single-scattering GGX loses, given back to every
  // light's specular lobe as to the environment's (a rough metal was 13-34 % darker under the
  // sun and the lights than under the sky: tools/fidelity).
  vec3 energyComp;
  float coat;          // KHR_materials_clearcoat
  vec3 coatN;
  float coatNoV;
  float coatRoughness;
  float coatAlpha;
  float baseScale;  // what the coat lets through to the base
  vec3 sheenColor;  // KHR_materials_sheen
  float sheenMax;
  float sheenA;
  float sheenE;
  float sheenScale;  // what the sheen lets through to the base
  vec3 transmitColor;  // KHR_materials_transmission (PN_TRANSMISSION only)
  // KHR_materials_diffuse_transmission: what the diffuse base passes on to the other side
  // (Lambertian): light arriving from behind the surface is scaled by it.
  vec3 backColor;
};

#if PN_IRIDESCENCE
// KHR_materials_iridescence: the film's Fresnel, evaluated once at n.v (as glTF's sample
// viewer does), mixed with the base's by the strength; given to every term as the normal
// reflectance whose Schlick curve passes through it at n.v, so the split sum, the lights and
// the albedo scaling all see it.
void applyIridescence(inout Layers L) {
  vec2 film = iridescenceFactors();
  if (film.x <= 0.0) return;
  float c = pow(1.0 - L.NoV, 5.0);
  vec3 fresnel = mix(F_Schlick(L.f0, L.f90, L.NoV),
                     thinFilmFresnel(uIridescence.y, L.NoV, film.y, L.f0), film.x);
  L.f0 = saturate((fresnel - L.f90 * c) / max(1.0 - c, 1e-3));
}
#endif

#if PN_ANISOTROPY
// KHR_materials_anisotropy: the lobe stretched along the direction (alpha_t from alpha to 1
// with the strength squared) for specularBrdf(), and for the environment a normal bent toward
// the stretch (the extension's sample implementation), less so on rough surfaces.
void setAnisotropy(Layers L) {
  vec3 an = anisotropyFactors();
  gAnisotropic = an.z > 0.0;
  gAnisoT = tangentDirection(L.n, an.xy);
  gAnisoB = cross(L.n, gAnisoT);
  gAlphaT = mix(L.alpha, 1.0, an.z * an.z);
  gAlphaB = L.alpha;
  vec3 anisotropicNormal = cross(cross(gAnisoB, L.v), gAnisoB);
  if (dot(anisotropicNormal, anisotropicNormal) < 1e-8) anisotropicNormal = L.n;
  float bend = pow(1.0 - an.z * (1.0 - L.perceptualRoughness), 4.0);
  gBentNormal = normalize(mix(anisotropicNormal, L.n, bend));
}
#endif

Layers surfaceLayers(SurfaceInputs s, vec3 v) {
  Layers L;
  L.n = s.normal;
  L.v = v;
  L.NoV = max(dot(L.n, v), 1e-4);
  L.diffuseColor = s.baseColor.rgb * (1.0 - s.metallic);
  vec4 dielectric = dielectricSpecular();
  L.f0 = mix(dielectric.rgb, s.baseColor.rgb, s.metallic);
  L.f90 = mix(dielectric.a, 1.0, s.metallic);
  L.perceptualRoughness = s.perceptualRoughness;
  L.alpha = s.perceptualRoughness * s.perceptualRoughness;
#if PN_IRIDESCENCE
  applyIridescence(L);
#endif
  vec3 dfgTerms = dfg(L.NoV, s.perceptualRoughness);
  // Fdez-Aguera's multiple-scattering term with the Fresnel average: energy that bounces k
  // times is coloured by Favg^k, so a coloured metal gets back less than f0 (1 / E - 1), which
  // is the same for a white one (a red rough metal read 16 % brighter than Cycles' multiscatter
  // GGX: tools/fidelity, BoxInterleaved).
  vec3 fAvg = L.f0 + (vec3(L.f90) - L.f0) / 21.0;
  float eMs = 1.0 - dfgTerms.z;
  L.energyComp = 1.0 + fAvg * eMs / (1.0 - fAvg * eMs);
  L.specularScale = (L.f0 * dfgTerms.x + L.f90 * dfgTerms.y) * L.energyComp;
  // glTF's fresnel_mix: the diffuse base only receives what the specular layer does not
  // reflect (albedo scaling with the directional specular albedo), so a white dielectric in a
  // white furnace reflects exactly the environment.
  L.diffuseColor *= vec3(1.0) - L.specularScale;
  L.backColor = vec3(0.0);
#if PN_DIFFUSE_TRANSMISSION
  // KHR_materials_diffuse_transmission: of the dielectric base's diffuse share, `a` leaves
  // through the other side with the transmission colour instead of the base colour.
  vec4 dt = diffuseTransmissionFactors();
  L.backColor = dt.rgb * dt.a * (1.0 - s.metallic) * (vec3(1.0) - L.specularScale);
  L.diffuseColor *= 1.0 - dt.a;
#endif
#if PN_ANISOTROPY
  setAnisotropy(L);
#endif
  L.transmitColor = vec3(0.0);
#if PN_TRANSMISSION
  // KHR_materials_transmission: of what the specular layer lets through, the share
  // `transmission` passes through the surface (tinted by the base colour) instead of being
  // diffused; it is added where the surfaces are composed (PN_TRANSMISSION 2).
  L.transmitColor = L.diffuseColor * transmissionFactor();
  L.diffuseColor -= L.transmitColor;
#endif
#if PN_CAPTURE
  // Probes store irradiance, so light leaves a captured surface view-independently: the
  // specular layer's directional albedo is reflected as if diffuse (energy kept, metals not
  // black), and no specular lobe is evaluated.
  L.diffuseColor += L.specularScale;
  L.f0 = vec3(0.0);
  L.f90 = 0.0;
  L.specularScale = vec3(0.0);
  L.energyComp = vec3(1.0);
#endif

  // KHR_materials_clearcoat: a GGX layer with F0 0.04 over the base, on its own normal (its
  // normal map, else the geometric normal). The base below gets what the coat lets through,
  // 1 - coat F(n.v), as the extension defines.
  // (Each factor function samples its textures: called once.)
  vec2 coatFactors = PN_CLEARCOAT == 0 ? vec2(0.0, 1.0) : clearcoatFactors();
#if PN_CAPTURE
  L.coat = 0.0;
#else
  L.coat = coatFactors.x;
#endif
  L.coatN = PN_CLEARCOAT == 0 ? L.n : clearcoatNormal();
  L.coatNoV = max(dot(L.coatN, v), 1e-4);
  L.coatRoughness =
      PN_CLEARCOAT == 0 ? 1.0 : clamp(coatFactors.y, MIN_PERCEPTUAL_ROUGHNESS, 1.0);
  L.coatAlpha = L.coatRoughness * L.coatRoughness;
  L.baseScale = PN_CLEARCOAT == 0 ? 1.0 : 1.0 - L.coat * F_Schlick(vec3(0.04), L.coatNoV).x;

  // KHR_materials_sheen: a Charlie lobe over the base, which receives what the sheen does not
  // reflect (glTF's albedo scaling, 1 - max(sheenColor) E(n.v)). Under the coat, like the base.
  vec4 sheen = PN_SHEEN == 0 ? vec4(0.0) : sheenFactors();
#if PN_CAPTURE
  L.sheenColor = vec3(0.0);
#else
  L.sheenColor = sheen.rgb;
#endif
  float sheenRoughness = sheen.a;
  L.sheenMax = max(L.sheenColor.r, max(L.sheenColor.g, L.sheenColor.b));
  L.sheenA = sheenAlpha(sheenRoughness);
  L.sheenE = L.sheenMax > 0.0 ? sheenAlbedo(L.NoV, sheenRoughness) : 0.0;
  L.sheenScale = 1.0 - L.sheenMax * L.sheenE;
  return L;
}

