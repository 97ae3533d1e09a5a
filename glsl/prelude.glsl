// Shared prelude of every Penumbra shader (GLSL ES 3.00, WebGL2). The composer puts
// "#version 300 es", the stage define (PN_VERTEX or PN_FRAGMENT) and the generated #defines
// before it.
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp samplerCube;
precision highp sampler2DShadow;
precision highp sampler2DArrayShadow;

const float PI = 3.14159265358979;
const float INV_PI = 0.31830988618379;

float saturate(float x) { return clamp(x, 0.0, 1.0); }
vec3 saturate(vec3 x) { return clamp(x, 0.0, 1.0); }
// Rec. 709 luminance of linear RGB.
float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
