// The KHR_materials_* extensions' factors times their textures (each function samples its
// textures: called once per shading), after chunks/material.glsl's core inputs, which
// include this file at their end.

// KHR_materials_clearcoat (factors): layer strength and perceptual roughness.
uniform float uClearcoat;
uniform float uClearcoatRoughness;
// KHR_materials_sheen (factors): colour (0 = no sheen) and perceptual roughness.
uniform vec3 uSheenColor;
uniform float uSheenRoughness;
// KHR_materials_transmission and KHR_materials_volume (factors): the transmitted share of the
// dielectric base, the volume's thickness (mesh units; 0 thin-walled), its index of refraction
// and Beer-Lambert attenuation (distance 0: none).
uniform float uTransmission;
uniform float uThickness;
uniform float uIor;
uniform float uAttenuationDistance;
uniform vec3 uAttenuationColor;
// KHR_materials_specular's colour: ((ior - 1) / (ior + 1))^2 specularColorFactor, before the
// clamp and the specular factor uDielectricF0 has applied (its texture multiplies in between).
uniform vec3 uSpecularColorF0;
// KHR_materials_dispersion: 20 / Abbe number (PN_DISPERSION only).
uniform float uDispersion;
// KHR_materials_iridescence: strength, the film's index, its thickness range (nm).
uniform vec4 uIridescence;
// KHR_materials_anisotropy: strength, cos and sin of the direction's rotation.
uniform vec3 uAnisotropy;
// KHR_materials_diffuse_transmission: colour (rgb) and the transmitted share (a).
uniform vec4 uDiffuseTransmission;

// The clearcoat's normal: its own normal map if it has one, else the geometric normal.
vec3 clearcoatNormal() {
  vec3 n = geometricNormal();
  if (!hasTexture(SLOT_COAT_NORMAL)) return n;
  return mappedNormal(n, layerTexel(SLOT_COAT_NORMAL).xyz * 2.0 - 1.0, uClearcoatNormalScale);
}

// KHR_materials_clearcoat: the layer's strength and perceptual roughness.
vec2 clearcoatFactors() {
  vec2 c = vec2(uClearcoat, uClearcoatRoughness);
  if (hasTexture(SLOT_COAT)) c.x *= layerTexel(SLOT_COAT).r;
  if (hasTexture(SLOT_COAT_ROUGHNESS)) c.y *= layerTexel(SLOT_COAT_ROUGHNESS).g;
  return c;
}

// KHR_materials_sheen: colour (rgb) and perceptual roughness (a).
vec4 sheenFactors() {
  vec4 c = vec4(uSheenColor, uSheenRoughness);
  if (hasTexture(SLOT_SHEEN_COLOR)) c.rgb *= srgbToLinear(layerTexel(SLOT_SHEEN_COLOR).rgb);
  if (hasTexture(SLOT_SHEEN_ROUGHNESS)) c.a *= layerTexel(SLOT_SHEEN_ROUGHNESS).a;
  return c;
}

// KHR_materials_ior and KHR_materials_specular: the dielectric reflectance at normal (rgb) and
// at grazing incidence (a).
vec4 dielectricSpecular() {
  if (!hasTexture(SLOT_SPECULAR) && !hasTexture(SLOT_SPECULAR_COLOR)) {
    return vec4(uDielectricF0, uDielectricF90);
  }
  float specular = uDielectricF90;
  if (hasTexture(SLOT_SPECULAR)) specular *= layerTexel(SLOT_SPECULAR).a;
  vec3 color = uSpecularColorF0;
  if (hasTexture(SLOT_SPECULAR_COLOR)) color *= srgbToLinear(layerTexel(SLOT_SPECULAR_COLOR).rgb);
  return vec4(min(color, vec3(1.0)) * specular, specular);
}

// KHR_materials_transmission: the transmitted share of the dielectric base.
float transmissionFactor() {
  return hasTexture(SLOT_TRANSMISSION) ? uTransmission * layerTexel(SLOT_TRANSMISSION).r
                                       : uTransmission;
}

// KHR_materials_volume: the thickness (mesh units; 0 thin-walled).
float thicknessFactor() {
  return hasTexture(SLOT_THICKNESS) ? uThickness * layerTexel(SLOT_THICKNESS).g : uThickness;
}

// KHR_materials_iridescence: the film's strength (x) and thickness in nanometres (y): the
// thickness texture's .g between the minimum and the maximum, else the maximum.
vec2 iridescenceFactors() {
  vec2 f = vec2(uIridescence.x, uIridescence.w);
  if (hasTexture(SLOT_IRIDESCENCE)) f.x *= layerTexel(SLOT_IRIDESCENCE).r;
  if (hasTexture(SLOT_IRIDESCENCE_THICKNESS)) {
    f.y = mix(uIridescence.z, uIridescence.w, layerTexel(SLOT_IRIDESCENCE_THICKNESS).g);
  }
  return f;
}

// KHR_materials_anisotropy: the direction in tangent space (xy, unit length: the texture's .rg
// in [-1, 1], else the tangent, turned counter-clockwise by the rotation) and the strength (z,
// times the texture's .b).
vec3 anisotropyFactors() {
  vec3 a = vec3(1.0, 0.0, uAnisotropy.x);
  if (hasTexture(SLOT_ANISOTROPY)) {
    vec3 t = layerTexel(SLOT_ANISOTROPY).rgb;
    a.xy = t.xy * 2.0 - 1.0;
    a.z *= t.b;
  }
  float len = length(a.xy);
  vec2 d = len > 1e-5 ? a.xy / len : vec2(1.0, 0.0);
  return vec3(uAnisotropy.y * d.x - uAnisotropy.z * d.y, uAnisotropy.z * d.x + uAnisotropy.y * d.y,
              saturate(a.z));
}

// The world direction of a tangent-space direction d on shading normal n (the vertex tangent
// frame, negated on back faces as mappedNormal does), perpendicular to n.
vec3 tangentDirection(vec3 n, vec2 d) {
  vec3 t = vTangent.xyz - n * dot(n, vTangent.xyz);
  if (dot(t, t) <= 1e-10) {
    vec3 a = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    t = a - n * dot(n, a);
  }
  t = normalize(t);
  vec3 b = cross(n, t) * (vTangent.w < 0.0 ? -1.0 : 1.0);
  if (!gl_FrontFacing) {
    t = -t;
    b = -b;
  }
  return normalize(t * d.x + b * d.y);
}

// KHR_materials_diffuse_transmission: colour (rgb) and the transmitted share (a).
vec4 diffuseTransmissionFactors() {
  vec4 f = uDiffuseTransmission;
  if (hasTexture(SLOT_DIFFUSE_TRANSMISSION)) f.a *= layerTexel(SLOT_DIFFUSE_TRANSMISSION).a;
  if (hasTexture(SLOT_DIFFUSE_TRANSMISSION_COLOR)) {
    f.rgb *= srgbToLinear(layerTexel(SLOT_DIFFUSE_TRANSMISSION_COLOR).rgb);
  }
  return f;
}
