#pragma once
// The accuracy study's files (docs/accuracy.md, "Files"): study.csv (a row per setting and backend,
// and the noise floor's), ladders.csv (a row per knob, metric and level) and study.h5 (all of it,
// with every frame's curves). Timings are kept apart from the data: the `time_*` columns of
// study.csv, and /timing in study.h5; the rest is the same bytes for the same records. Each file is
// written under a temporary name and renamed.
#include <string>
#include <utility>
#include <vector>

#include "core/study/study_analysis.h"

namespace bleedsim {

void write_study_csv(const std::string& path, const Study& study, const StudyResult& result);
void write_ladders_csv(const std::string& path, const StudyResult& result);
void write_study_hdf5(const std::string& path, const Study& study, const StudyResult& result,
                      const std::vector<std::pair<std::string, std::string>>& attributes);

// All three into `folder`.
void write_study_files(const std::string& folder, const Study& study, const StudyResult& result,
                       const std::vector<std::pair<std::string, std::string>>& attributes);

}  // namespace bleedsim
