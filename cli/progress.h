#pragma once
#include <chrono>

namespace bleedsim::cli {

// A one-line progress display on a terminal ("frame 45/120  37%  12.3 ms/frame  eta 1.1 s"),
// redrawn at most ten times a second and cleared at the end. Silent when not enabled.
class Progress {
 public:
  Progress(long total_frames, bool enabled);
  void update(long frames_done);
  void clear();

 private:
  long total_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace bleedsim::cli
