// A one-line progress bar on stderr ("frame i of m, time left"; "job i of n" for a batch),
// shown only on a terminal.
#pragma once

#include <chrono>
#include <deque>
#include <string>
#include <utility>

namespace penumbra::tools {

class ProgressBar {
 public:
  ProgressBar(std::string label, int total, bool enabled, std::string unit = "frame");
  // `total` may change as it goes (an automatic view's expected frames).
  void update(int done, int total = 0);
  void finish();

 private:
  std::string label_;
  std::string unit_;
  int total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  // The last few updates (done, seconds since start): the units left are priced at their mean
  // cost, as the web viewer does (web/lib/progress.mjs): early frames are dearer.
  std::deque<std::pair<int, double>> recent_;
};

}  // namespace penumbra::tools
