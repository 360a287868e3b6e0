#include "cli/progress.h"

#include <cstdio>

namespace bleedsim::cli {

Progress::Progress(long total_frames, bool enabled)
    : total_(total_frames), enabled_(enabled), start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

void Progress::update(long frames_done) {
  if (!enabled_ || frames_done <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (frames_done < total_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  const double elapsed_s = std::chrono::duration<double>(now - start_).count();
  const double ms_per_frame = 1000.0 * elapsed_s / double(frames_done);
  const double eta_s = ms_per_frame * double(total_ - frames_done) / 1000.0;
  std::fprintf(stderr, "\r  frame %ld/%ld  %3.0f%%  %.1f ms/frame  eta %.1f s   ", frames_done, total_,
               100.0 * double(frames_done) / double(total_), ms_per_frame, eta_s);
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::clear() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r%*s\r", 70, "");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace bleedsim::cli
