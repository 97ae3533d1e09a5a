// A one-line progress bar on stderr ("frame i of m, time left"), shown only on a terminal.
#pragma once

#include <chrono>
#include <string>

namespace penumbra::tools {

class ProgressBar {
 public:
  ProgressBar(std::string label, int total, bool enabled);
  void update(int done);
  void finish();

 private:
  std::string label_;
  int total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace penumbra::tools
