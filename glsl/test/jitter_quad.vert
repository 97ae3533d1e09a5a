// Self-test: a triangle in clip space, shifted by a sub-pixel jitter (in NDC units).
layout(location = 0) in vec2 aPosition;
uniform vec2 uJitter;
void main() { gl_Position = vec4(aPosition + uJitter, 0.0, 1.0); }
