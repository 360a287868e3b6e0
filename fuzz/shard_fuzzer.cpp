// The shard file reader (core/scaleout/shard_file.h: decode_shard, what read_shard and so `bleedsim
// study merge` run on each file) on any bytes, then what the merge decodes from a shard it accepts:
// the study's description (cli/study_description.h) and each job's record (core/study/job_record.h).
// The shard and description readers must refuse bytes with an InputError, the record's reader with
// the std::runtime_error that the analysis reports, or accept them: never crash, read out of bounds,
// leak or allocate more than the bytes can hold.
//
// A mutation almost always breaks the file's checksum, which the reader checks before the body, so
// each input is read twice: as it is (the prologue's checks and the "damaged" refusal), then, where
// it is long enough, with its length and checksum rewritten to fit its bytes (the body's parser).
// The seeds are real shards of a small study (fuzz/seeds/, scripts/make-shard-seeds).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "cli/study_description.h"
#include "core/runtime/hash.h"
#include "core/runtime/input_error.h"
#include "core/scaleout/shard_file.h"
#include "core/study/job_record.h"

namespace {

// The layout of shard_file.cpp: the magic (8 bytes), the version (4), the file's length (8) and, at
// the end, the FNV-1a 64 of everything before it (8), each little-endian.
constexpr std::size_t kLengthAt = 12, kPrologueBytes = 20, kChecksumBytes = 8;

void put_u64(std::uint8_t* at, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) at[i] = std::uint8_t(v >> (8 * i));
}

std::vector<std::uint8_t> with_length_and_checksum_that_fit(std::vector<std::uint8_t> bytes) {
  put_u64(bytes.data() + kLengthAt, bytes.size());
  const std::size_t body = bytes.size() - kChecksumBytes;
  put_u64(bytes.data() + body, bleedsim::fnv1a64(bytes.data(), body));
  return bytes;
}

void read_as_the_merge_does(const std::vector<std::uint8_t>& bytes) {
  bleedsim::ShardContents shard;
  try {
    shard = bleedsim::decode_shard(bytes, "fuzzed.bleedshard");
  } catch (const bleedsim::InputError&) {
    return;
  }
  try {
    bleedsim::cli::read_study_description(shard.study, "fuzzed.bleedshard");
  } catch (const bleedsim::InputError&) {
  }
  for (const bleedsim::JobResult& result : shard.results) {
    try {
      bleedsim::deserialize(result.record);
    } catch (const std::runtime_error&) {
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::uint8_t> bytes(data, data + size);
  read_as_the_merge_does(bytes);
  if (size >= kPrologueBytes + kChecksumBytes) read_as_the_merge_does(with_length_and_checksum_that_fit(bytes));
  return 0;
}
