// How much of frame 1 the displayed image holds in a view with stochastic transparency. Frame 1
// alpha-blends the BLEND surfaces (a smooth picture); each later frame keeps a surface's
// fragment or not (glsl/chunks/coverage.glsl), so the mean of 2 or 3 frames showed glass panes
// as salt and pepper that frame 1 did not have (the glass scene's grain 2x frame 1's at frame
// 3). Frames 2..kFirstFrameHold show mix(mean, frame 1, firstFrameHold(n)), fading to the mean
// as the coverage fills its first stratified block; from frame kFirstFrameHold + 1 on, and in
// every view without BLEND surfaces, the display is the mean. The mean itself, the convergence
// measure and the linear (EXR) output are never mixed, so stops and the converged image stay
// as they were. GL-free; the renderer draws the mix (passes/accumulate_pass.h).
#pragma once

namespace penumbra::progressive {

// The coverage's stratification block (COVERAGE_BLOCK of glsl/chunks/coverage.glsl): frame 1
// plus one block of stochastic frames.
inline constexpr int kFirstFrameHold = 17;

// The weight of frame 1 mixed into the displayed image after n frames (n >= 1):
// (1 - (n - 1) / (kFirstFrameHold - 1))^2, 0 at frame 1 (the mean is frame 1) and from
// kFirstFrameHold on. Frame 1's share of what is shown is then 1/n + hold (1 - 1/n): 0.84 at
// frame 3, 0.33 at frame 9, 1/17 at frame 17, where it meets the mean's.
double firstFrameHold(int n);

}  // namespace penumbra::progressive
