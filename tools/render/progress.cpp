#include "progress.h"

#include <algorithm>
#include <cstdio>
#include <utility>

namespace penumbra::tools {

ProgressBar::ProgressBar(std::string label, int total, bool enabled, std::string unit)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      total_(total),
      enabled_(enabled),
      start_(std::chrono::steady_clock::now()) {}

void ProgressBar::update(int done, int total) {
  if (total > 0) total_ = total;
  if (!enabled_ || total_ <= 0) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (recent_.empty() || recent_.back().first != done) recent_.emplace_back(done, elapsed);
  if (recent_.size() > 9) recent_.pop_front();  // eight intervals
  const auto& [firstDone, firstTime] = recent_.front();
  const double each = done > firstDone ? (elapsed - firstTime) / (done - firstDone)
                      : done > 0      ? elapsed / done
                                      : 0.0;
  const double left = each * std::max(total_ - done, 0);
  const int width = 30;
  const int filled = width * std::min(done, total_) / total_;
  std::fprintf(stderr, "\r%s [%.*s%*s] %s %d of %d, %.1f s left   ", label_.c_str(), filled,
               "##############################", width - filled, "", unit_.c_str(), done, total_,
               left);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (enabled_) std::fprintf(stderr, "\n");
}

}  // namespace penumbra::tools
