#pragma once
// A job's result as the distribution layer carries it: the record the job made (opaque bytes; the
// caller's format) and where it was made (provenance, never part of the data).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/scaleout/byte_codec.h"

namespace bleedsim {

struct JobOrigin {
  int rank = 0;          // the MPI rank that ran it (0 in one process)
  std::string host;      // that rank's host name
  int cuda_device = -1;  // the CUDA device that rank was given; -1 where it sees none
  double seconds = 0;    // the job's wall time: differs run to run, so it stays beside the data
};

struct JobResult {
  std::size_t job = 0;
  std::vector<std::uint8_t> record;
  JobOrigin origin;
};

// An origin as bytes, for the shard files and the messages between ranks.
void write_origin(ByteWriter& out, const JobOrigin& origin);
JobOrigin read_origin(ByteReader& in, const std::string& what);

}  // namespace bleedsim
