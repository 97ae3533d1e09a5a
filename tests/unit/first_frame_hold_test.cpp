// The displayed image's hold on frame 1 in views with stochastic transparency
// (progressive/first_frame_hold.h).
#include "progressive/first_frame_hold.h"

#include <gtest/gtest.h>

namespace penumbra::progressive {
namespace {

// Frame 1's share of the displayed image, the mean's 1/n and the hold on top.
double firstShare(int n) { return 1.0 / n + firstFrameHold(n) * (1.0 - 1.0 / n); }

TEST(FirstFrameHoldTest, FadesFromFrameOneToTheMeanWithinOneCoverageBlock) {
  EXPECT_EQ(firstFrameHold(1), 0.0) << "frame 1 is the mean";
  for (int n = 2; n < kFirstFrameHold; ++n) {
    EXPECT_GT(firstFrameHold(n), 0.0) << n;
    EXPECT_LT(firstFrameHold(n), 1.0) << n;
    if (n > 2) {
      EXPECT_LT(firstFrameHold(n), firstFrameHold(n - 1)) << n;
    }
    // What is shown never gives frame 1 less than the mean does, and falls frame by frame.
    EXPECT_GE(firstShare(n), 1.0 / n) << n;
    EXPECT_LT(firstShare(n), firstShare(n - 1)) << n;
  }
  for (int n = kFirstFrameHold; n <= 4096; ++n) EXPECT_EQ(firstFrameHold(n), 0.0) << n;
}

// What it is for: two stochastic frames carry about a sixth of what frame 3 shows (two thirds
// in the mean), and frame 1 leads to about frame 9.
TEST(FirstFrameHoldTest, TheFirstStochasticFramesCarryLittleOfThePicture) {
  EXPECT_LT(1.0 - firstShare(3), 0.2);
  EXPECT_GT(firstShare(8), 0.3);
  EXPECT_LT(firstShare(12), 0.2);
}

}  // namespace
}  // namespace penumbra::progressive
