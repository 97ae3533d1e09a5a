// Self-test: irradiance per unit luminance from one area light at points along a line,
// one point per pixel column (chunks/area_lights.glsl in isolation).
#include "chunks/brdf.glsl"
#include "chunks/area_lights.glsl"
uniform vec3 uLightPos;
uniform vec3 uLightDir;
uniform vec3 uLightRight;
uniform vec3 uLightUp;
uniform vec2 uLightSize;
uniform bool uDisk;
uniform vec3 uStart;   // first point
uniform vec3 uStep;    // per pixel column
uniform vec3 uNormal;
out vec4 fragColor;
void main() {
  AreaLight L;
  L.position = uLightPos;
  L.direction = uLightDir;
  L.right = uLightRight;
  L.up = uLightUp;
  L.size = uLightSize;
  L.shape = uDisk ? PN_LIGHT_DISK : PN_LIGHT_RECT;
  vec3 p = uStart + uStep * floor(gl_FragCoord.x);
  fragColor = vec4(areaLightIrradiance(L, p, normalize(uNormal)), 0.0, 0.0, 1.0);
}
