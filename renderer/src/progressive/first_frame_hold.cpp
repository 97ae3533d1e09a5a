#include "progressive/first_frame_hold.h"

#include "penumbra/error.h"

namespace penumbra::progressive {

double firstFrameHold(int n) {
  PN_CHECK(n >= 1, "firstFrameHold: frames count from 1");
  if (n == 1 || n >= kFirstFrameHold) return 0.0;
  const double t = 1.0 - static_cast<double>(n - 1) / (kFirstFrameHold - 1);
  return t * t;
}

}  // namespace penumbra::progressive
