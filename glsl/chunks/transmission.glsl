// KHR_materials_transmission and KHR_materials_volume: what a transmissive surface shows of
// the scene behind it. The opaque scene of this frame is copied before transmissive surfaces
// are composed (passes/lighting_pass.h), so the surface looks it up at the point its refracted
// ray reaches. One microfacet normal per pixel and frame: rough glass blurs what is behind it
// as the frames accumulate, with no mip chain and no blur pass.
//   thin-walled (thickness 0): the reflection lobe mirrored through the surface, continued to
//     the opaque surface behind (the prepass's depth) or, over the background, to infinity;
//   volume (thickness > 0): refracted into the medium (ior), through a sphere of the
//     thickness's diameter (in world units: the factor times the item's scale), attenuated by
//     Beer-Lambert along the chord, refracted out and continued like a thin-walled ray.
uniform sampler2D uBehind;     // this frame's radiance of everything drawn before
uniform sampler2D uGlassLight;  // the transmissive surfaces' own light (reflection, diffuse)
uniform int uBehindDepthValid;  // uPrepass holds this view's linear depth (not in frame 1)
uniform mat4 uModel;
uniform mat4 uViewProj;  // this frame's, jittered like the copy
#if !PN_OCCLUSION
uniform sampler2D uPrepass;  // xyz view-space normal, w linear depth (0 = background)
uniform mat4 uView;
uniform vec2 uViewportSize;  // the part of the targets this frame draws
#endif

// Radiance arriving through the surface at p (unit normal n facing the viewer, toward-viewer
// v), and its Beer-Lambert transmittance.
// Through microfacet normal h, with index ior (thickness: the volume's, 0 thin-walled).
vec3 radianceThrough(vec3 p, vec3 n, vec3 v, vec3 h, float ior, float thickness) {
  ivec2 here = ivec2(gl_FragCoord.xy);
  ivec2 size = ivec2(uViewportSize);  // of the copy, only this frame's drawn part
  float ownDepth = -(uView * vec4(p, 1.0)).z;
  float behindDepth = uBehindDepthValid != 0 ? texelFetch(uPrepass, here, 0).w : -1.0;
  vec3 attenuation = vec3(1.0);
  vec3 start = p;  // where the ray leaves the surface (or the volume)
  vec3 dir;        // and its direction from there
  if (thickness > 0.0) {
    // The volume is taken for a sphere of diameter `thickness` (world units: the factor times
    // the item's scale) entered here: the chord shortens toward the silhouette, and the ray
    // refracts again where it leaves through the far side, whose normal follows from the chord
    // (n' = n - 2 (n.d) d). A ball then shows the inverted scene behind it, as glass does; a
    // slab seen face-on passes the ray straight through.
    vec3 inside = refract(-v, h, 1.0 / max(ior, 1.0));
    if (dot(inside, inside) < 1e-6) inside = -v;
    float scale = pow(abs(determinant(mat3(uModel))), 1.0 / 3.0);
    float chord = thickness * scale * max(-dot(n, inside), 0.05);
    if (uAttenuationDistance > 0.0) {
      attenuation = pow(max(uAttenuationColor, vec3(1e-6)), vec3(chord / uAttenuationDistance));
    }
    start = p + inside * chord;
    vec3 exitNormal = n - 2.0 * dot(n, inside) * inside;
    dir = refract(inside, -exitNormal, max(ior, 1.0));
    if (dot(dir, dir) < 1e-6) dir = inside;  // total internal reflection: kept going
  } else {
    vec3 r = reflect(-v, h);
    dir = r - 2.0 * dot(r, n) * n;  // the reflection lobe mirrored through the surface
  }
  vec4 clip;
  if (behindDepth == 0.0) {
    clip = uViewProj * vec4(dir, 0.0);  // the background: a direction, at infinity
  } else if (behindDepth < 0.0) {
    clip = uViewProj * vec4(start, 1.0);  // no depth yet (frame 1): where the ray leaves
  } else {
    // Along the ray, as far as the view depth to the surface behind this pixel asks.
    float startDepth = -(uView * vec4(start, 1.0)).z;
    float along = max(-(mat3(uView) * dir).z, 0.05);
    float travel = max(behindDepth - startDepth, 0.0) / along;
    clip = uViewProj * vec4(start + dir * travel, 1.0);
  }
  ivec2 q = here;
  if (clip.w > 1e-6) {
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    // Off screen: what is straight behind stands in (the probe volume does not hold the
    // background's detail).
    if (all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0)))) {
      q = clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1);
      // Something opaque in front of this surface: it is not what the ray reaches.
      float qDepth = uBehindDepthValid != 0 ? texelFetch(uPrepass, q, 0).w : -1.0;
      if (qDepth > 0.0 && qDepth < ownDepth) q = here;
    }
  }
  return texelFetch(uBehind, q, 0).rgb * attenuation;
}

vec3 transmittedRadiance(vec3 p, vec3 n, vec3 v, float alpha, float ior) {
  vec3 h = tangentFrame(n) * sampleGgxHalfVector(pixelSample(gl_FragCoord.xy, 9.0), alpha);
  float thickness = thicknessFactor();
#if PN_DISPERSION
  // KHR_materials_dispersion: red and blue refract with indices (ior - 1) * 0.025 * dispersion
  // below and above ior (the extension's three-index model of the Abbe number), each channel
  // from its own ray, all three every frame (a channel a frame would tint the first picture).
  if (thickness > 0.0) {
    float spread = (ior - 1.0) * 0.025 * uDispersion;
    return vec3(radianceThrough(p, n, v, h, ior - spread, thickness).r,
                radianceThrough(p, n, v, h, ior, thickness).g,
                radianceThrough(p, n, v, h, ior + spread, thickness).b);
  }
#endif
  return radianceThrough(p, n, v, h, ior, thickness);
}
