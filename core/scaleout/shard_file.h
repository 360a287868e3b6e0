#pragma once
// Shards: a study split over separate processes that never talk (a Slurm job array), each running
// the jobs assign_jobs gives its part and writing them to a shard file; merge_shards then puts the
// files back together in job order. A shard file holds, after a magic, a format version and its own
// length: the study's fingerprint and description, the job count, the shard's i and K, and each of
// its jobs' index, origin and record; then an FNV-1a 64 checksum of everything before it. It is
// written under a temporary name and renamed when whole, so a shard file on disk is complete.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/scaleout/job_result.h"

namespace bleedsim {

// Part `index` of `count` (0 ≤ index < count), as in `--shard index/count`.
struct ShardId {
  int index = 0;
  int count = 1;
};

// "2/8" as {2, 8}. Throws InputError at "--shard" for anything else ("8/8", "-1/8", "2/0", "2").
ShardId parse_shard(const std::string& text);
// "shard-2-of-8.bleedshard" ("shard-02-of-12.bleedshard": the names sort in shard order).
std::string shard_file_name(ShardId shard);

struct ShardContents {
  std::string fingerprint;         // names the study: a hash of the scenario, the files it names and the options
  std::vector<std::uint8_t> study; // what the merge needs to analyse the records (the caller's bytes)
  std::size_t job_count = 0;       // jobs in the whole study
  ShardId shard;
  std::vector<JobResult> results;  // the shard's jobs, ascending
};

// Writes `path` whole or not at all (a temporary beside it, flushed to disk, then renamed over it).
// Throws std::invalid_argument for results out of order or past job_count, std::runtime_error
// naming the file and the OS error when it cannot be written.
void write_shard(const std::string& path, const ShardContents& contents);

// Throws InputError naming the file for one that is missing, not a regular file (refused unopened),
// unreadable, not a shard file, of another format version, cut off, or damaged (its checksum).
ShardContents read_shard(const std::string& path);
// read_shard's checks of a shard file's bytes, `path` naming it in the messages.
ShardContents decode_shard(const std::vector<std::uint8_t>& bytes, const std::string& path);

struct MergedShards {
  std::string fingerprint;
  std::vector<std::uint8_t> study;
  std::size_t shard_count = 0;
  std::vector<JobResult> results;  // every job of the study, in job order
};

// The shard files of one study, in any order. Throws InputError naming the file at fault when a
// file cannot be read (as read_shard), when files disagree on the study (fingerprint,
// description, job count, K), when a shard comes twice or is missing, and when a job is in two
// files or in none.
MergedShards merge_shards(const std::vector<std::string>& paths);

}  // namespace bleedsim
