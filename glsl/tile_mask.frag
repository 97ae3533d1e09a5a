// Adaptive frames (Renderer::Impl::skipTiles): drawn with gl::StencilMode::Mark and colour
// writes off, it marks the stencil of the tiles of PN_TILE x PN_TILE pixels whose mask texel is
// set; later frames shade and accumulate only where the stencil is 0.
uniform sampler2D uMask;
out vec4 fragColor;

void main() {
  if (texelFetch(uMask, ivec2(gl_FragCoord.xy) / PN_TILE, 0).r < 0.5) discard;
  fragColor = vec4(0.0);
}
