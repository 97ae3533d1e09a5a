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
};

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
  vec3 dfgTerms = dfg(L.NoV, s.perceptualRoughness);
  L.specularScale =
      (L.f0 * dfgTerms.x + L.f90 * dfgTerms.y) * (1.0 + L.f0 * (1.0 / dfgTerms.z - 1.0));
  // glTF's fresnel_mix: the diffuse base only receives what the specular layer does not
  // reflect (albedo scaling with the directional specular albedo), so a white dielectric in a
  // white furnace reflects exactly the environment.
  L.diffuseColor *= vec3(1.0) - L.specularScale;
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

