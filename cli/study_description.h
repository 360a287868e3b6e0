#pragma once
// What a shard carries of its study (core/scaleout/shard_file.h keeps it as bytes) so that `bleedsim
// study merge` builds the same study from any folder: the scenario's text and its absolute path (which
// the files it names are found beside), the --knob texts, the backends as they were resolved (a merge
// needs no device), the duration, the seeds and the threads.
#include <cstdint>
#include <string>
#include <vector>

#include "core/io/scenario.h"
#include "core/study/study.h"

namespace bleedsim::cli {

// "substeps=10,20,40" as a knob and its levels, as --knob gives it. Throws InputError at "--knob"
// for a knob that is not one or a level that is not a decimal number; what the levels must be beside
// (in range, each once) the study checks.
KnobLevels parse_knob(const std::string& text);

struct DescribedStudy {
  std::string scenario_path;
  std::string scenario_text;
  StudySpec spec;
};

std::vector<std::uint8_t> describe_study(const Scenario& scenario, const std::vector<std::string>& knobs,
                                         const StudySpec& spec);
// Throws InputError under `shard` (the file the bytes came from) for a description of another format
// or one cut off, and as parse_knob for its knobs.
DescribedStudy read_study_description(const std::vector<std::uint8_t>& bytes, const std::string& shard);

}  // namespace bleedsim::cli
