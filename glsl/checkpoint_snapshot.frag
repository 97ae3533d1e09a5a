// Keeps an automatic view's checkpoint (Renderer::Impl::measureTiles): the displayed image of
// the running mean, for a later checkpoint's convergence measure (convergence.frag).
#include "chunks/displayed.glsl"
uniform sampler2D uCurrent;  // the running mean, radiance
out vec4 fragColor;

void main() {
  fragColor = vec4(displayed(texelFetch(uCurrent, ivec2(gl_FragCoord.xy), 0)), 1.0);
}
