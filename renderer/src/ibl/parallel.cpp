#include "ibl/parallel.h"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace penumbra::ibl {

int resolveThreads(int requested) {
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
  // A wasm build without pthreads cannot start threads at all.
  (void)requested;
  return 1;
#else
  if (requested > 0) return std::min(requested, 256);
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(std::min(hw, 256u));
#endif
}

void parallelFor(int count, int threads, const std::function<void(int)>& body) {
  if (count <= 0) return;
  const int n = std::min(resolveThreads(threads), count);
  if (n <= 1) {
    for (int i = 0; i < count; ++i) body(i);
    return;
  }
  std::atomic<int> next{0};
  const auto worker = [&] {
    for (int i = next++; i < count; i = next++) body(i);
  };
  std::vector<std::thread> pool;
  pool.reserve(n - 1);
  for (int t = 1; t < n; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

}  // namespace penumbra::ibl
