// The mean after a reduced frame 1 (ProgressiveSettings::previewScale): that frame, which
// covers the bottom-left uDrawnSize texels of uCurrent, upsampled bilinearly to the whole
// target. Written with texel fetches: float targets need not be filterable.
uniform sampler2D uCurrent;
uniform vec2 uDrawnSize;  // whole texels
in vec2 vUv;
out vec4 fragColor;
void main() {
  ivec2 size = ivec2(uDrawnSize);
  vec2 p = vUv * uDrawnSize - 0.5;  // in the drawn texels' centres
  vec2 f = fract(p);
  ivec2 last = size - 1;
  ivec2 a = clamp(ivec2(floor(p)), ivec2(0), last);
  ivec2 b = clamp(ivec2(floor(p)) + 1, ivec2(0), last);
  vec4 bottom = mix(texelFetch(uCurrent, a, 0), texelFetch(uCurrent, ivec2(b.x, a.y), 0), f.x);
  vec4 top = mix(texelFetch(uCurrent, ivec2(a.x, b.y), 0), texelFetch(uCurrent, b, 0), f.x);
  fragColor = mix(bottom, top, f.y);
}
