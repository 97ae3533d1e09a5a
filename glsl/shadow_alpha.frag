// Shadow maps of MASK and BLEND surfaces: depth only, with the same cut-out and stochastic
// coverage as shading, so leaves cast cut-out shadows and a surface of alpha a blocks a light
// sample with probability a (its shadow converges to 1 - a of the light).
#include "chunks/brdf.glsl"
#include "chunks/material.glsl"
void main() { alphaTest(baseColor().a); }
