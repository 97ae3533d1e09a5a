// Shadow maps of MASK and BLEND surfaces: depth only, with the same cut-out and stochastic
// coverage as shading, so leaves cast cut-out shadows and a surface of alpha a blocks a light
// sample with probability a (its shadow converges to 1 - a of the light).
// Transmissive surfaces likewise block with probability 1 - what they transmit.
#include "chunks/brdf.glsl"
#include "chunks/material.glsl"
// A transmissive surface passes what it transmits of a light sample (a grey estimate with the
// same coverage scheme: tinted shadows, refraction and caustics are not modelled).
void main() {
  vec4 c = baseColor();
  alphaTest(c.a);
  if (uTransmission > 0.0) {
    float passes = transmissionFactor() * (1.0 - saturate(uMetallicFactor)) * dot(c.rgb, vec3(1.0 / 3.0)) *
                   (1.0 - max(uDielectricF0.r, max(uDielectricF0.g, uDielectricF0.b)));
    if (!coverageKept(1.0 - passes)) discard;
  }
}
