#pragma once
// What a run writes and where (docs/scenario-format.md, [output]; docs/output-format.md). Not part
// of the Scene: the same scene may be written anywhere, or not at all by a host.
#include <string>
#include <vector>

#include "core/runtime/params.h"

namespace bleedsim {

struct OutputSpec {
  std::string dir;                  // where outputs go; relative paths are to the working directory
  bool hdf5 = true;                 // frames.h5 in dir
  int png_every = 0;                // 0: no PNGs; N: frame 0, every Nth frame, and the last
  int contact_sheet = 0;            // 0: none; N: N frames from first to last in one PNG
  int deflate_level = 4;            // HDF5 gzip level 0–9
  std::vector<std::string> fields;  // fields written to HDF5 besides the frame; empty = all
};

// The [output] table.
const ParamTable<OutputSpec>& output_table();

}  // namespace bleedsim
