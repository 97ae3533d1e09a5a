// Self-test: writes a constant colour, accumulated with additive blending.
uniform vec4 uColor;
out vec4 fragColor;
void main() { fragColor = uColor; }
