// Stochastic transparency (Enderton, Sintorn, Shirley, Luebke, I3D 2010): a BLEND surface
// covers a pixel with probability alpha, decided afresh each frame, so the running mean of
// the frames converges to the order-independent composite. Every pass that draws the surface
// in a frame (prepass, each lighting batch) uses the same frame and stream, so they agree on
// which fragments exist; each shadow map of the frame has a stream of its own.
//
// Camera passes stratify over time: frames are taken in blocks of 16, and within a block
// each pixel and surface visits the 16 strata of [0, 1) in its own random order (a hashed
// permutation), jittered inside the stratum. A single layer's coverage is then exact to 1/16
// after every block, and different surfaces (independent orders: a Latin-hypercube pairing)
// still converge to the product of their probabilities.
//
// Shadow maps stratify over space instead: a receiver looks through a different texel for
// every light sample, so per-texel stratification over time would not reach it. Each map
// splits its texels into 2x2 blocks; a block's four texels take the four strata of [0, 1) in
// a random order with one random rotation, so every block keeps alpha of the surface to
// within a quarter and the PCF lookup already sees about alpha. Block orders are independent,
// so no pattern repeats (an ordered-dither matrix left stripes), and the rotation makes every
// texel's mean exact.
uniform int uCoverageFrame;   // < 0: no stochastic coverage (frame 1 alpha-blends instead)
uniform int uCoverageStream;  // 0: the camera's passes; 1, 2, ...: this frame's shadow maps
uniform int uLayer;           // per draw item: independent decisions for different surfaces

const uint COVERAGE_BLOCK = 16u;

// PCG-based 3D hash (Jarzynski & Olano, JCGT 2020).
uvec3 pcg3d(uvec3 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  return v;
}

// A bijection of [0, 16) chosen by `key`: each step (xor, odd multiply, add, xorshift) is
// invertible modulo 16, and the key enters several of them.
uint permute16(uint i, uint key) {
  i = (i ^ key) & 15u;
  i = (i * ((key >> 4u) | 1u) + (key >> 8u)) & 15u;
  i ^= i >> 2u;
  i = (i * 13u + (key >> 12u)) & 15u;
  i ^= i >> 1u;
  i = (i * ((key >> 16u) | 1u) + (key >> 20u)) & 15u;
  i ^= i >> 2u;
  return (i * 5u + (key >> 24u)) & 15u;
}

// A bijection of [0, 4) chosen by `key` (all 24 orders occur).
uint permute4(uint i, uint key) {
  i = (i ^ key) & 3u;
  i ^= (i >> 1u) & (key >> 2u) & 1u;
  i = (i * ((key >> 3u) | 1u) + (key >> 5u)) & 3u;
  i ^= (i >> 1u) & (key >> 7u) & 1u;
  return (i + (key >> 8u)) & 3u;
}

// Front and back faces of one closed mesh are separate layers.
bool coverageKept(float alpha) {
  if (uCoverageFrame < 0) return true;
  uint layer = uint(uLayer) * 2u + (gl_FrontFacing ? 1u : 0u);
  uint frame = uint(uCoverageFrame);
  uvec2 pixel = uvec2(gl_FragCoord.xy);
  if (uCoverageStream > 0) {
    uvec3 h = pcg3d(uvec3(pixel >> 1u, (layer * 0x9E3779B9u) ^ (uint(uCoverageStream) * 0x85EBCA6Bu) ^
                                           (frame * 0xC2B2AE35u)));
    uint rank = permute4((pixel.x & 1u) | ((pixel.y & 1u) << 1u), h.x);
    return fract((float(rank) + 0.5) * 0.25 + float(h.y >> 8u) * (1.0 / 16777216.0)) < alpha;
  }
  uvec3 h = pcg3d(uvec3(pixel, (layer * 0x9E3779B9u) ^ (uint(uCoverageStream) * 0x85EBCA6Bu) ^
                                   ((frame / COVERAGE_BLOCK) * 0xC2B2AE35u)));
  uint stratum = permute16(frame % COVERAGE_BLOCK, h.x);
  float jitter = float(pcg3d(uvec3(h.yz, frame)).x >> 8u) * (1.0 / 16777216.0);
  return (float(stratum) + jitter) * (1.0 / float(COVERAGE_BLOCK)) < alpha;
}
