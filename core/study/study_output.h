#pragma once
// The accuracy study's files (docs/accuracy.md): study.csv, one row per setting and backend, and
// study.h5 with every frame's time and errors. Each is written under a temporary name and renamed.
#include <string>
#include <utility>
#include <vector>

#include "core/study/study.h"

namespace bleedsim {

// One run summed up over its frames: what a CSV row and a plot point show.
struct StudySummary {
  long frames = 0;
  double ms_p50 = 0, ms_p99 = 0, frame_budget_p99_pct = 0;
  FrameErrors mean{};    // each error's mean over the frames (NaN where not applicable)
  double psnr_db = 0;    // from the mean squared error over all frames
  FrameErrors knob_mean{};  // the same against the knob's finest setting (NaN without it)
  double knob_psnr_db = 0;
};
StudySummary summarize(const StudyRun& run);

void write_study_csv(const std::string& path, const std::string& scene_name, const std::vector<StudyRun>& runs);

void write_study_hdf5(const std::string& path, const Study& study, const std::vector<StudyRun>& runs,
                      const std::vector<std::pair<std::string, std::string>>& attributes);

}  // namespace bleedsim
