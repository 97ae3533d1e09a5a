// A minimal parallel-for over std::thread for the IBL code. Work items are handed out in
// chunks through an atomic counter; each item must write only its own outputs, so results do
// not depend on the thread count or on scheduling.
#pragma once

#include <functional>

#include "penumbra/ibl.h"  // resolveThreads

namespace penumbra::ibl {

// Calls body(i) for every i in [0, count), on up to `threads` threads (the caller's included).
void parallelFor(int count, int threads, const std::function<void(int)>& body);

}  // namespace penumbra::ibl
