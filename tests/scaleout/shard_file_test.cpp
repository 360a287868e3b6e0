// Shard files (core/scaleout/shard_file.cpp): a study's jobs written as K shards merge back to every
// record in job order, bit for bit; every kind of wrong file or set of files is refused, naming it.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/runtime/hash.h"
#include "core/runtime/input_error.h"
#include "core/scaleout/job_assignment.h"
#include "core/scaleout/shard_file.h"
#include "tests/scaleout/toy_jobs.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;

fs::path scratch() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(test::binary_dir()) / "test-scratch" / info->test_suite_name() / info->name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

const std::vector<std::uint8_t> kStudy = {'s', 'c', 'e', 'n', 'e', '\0', 1, 2, 3};

// Shard `index` of `count` of a study of `jobs` toy jobs, split as run_jobs would split it.
ShardContents toy_shard(std::size_t jobs, int index, int count, const std::string& fingerprint = "f00d") {
  ShardContents shard{fingerprint, kStudy, jobs, {index, count}, {}};
  for (const std::size_t job : jobs_of_part(assign_jobs(test::toy_costs(jobs), count), index))
    shard.results.push_back(JobResult{job, test::toy_record(job), JobOrigin{index, "node" + std::to_string(index), 1, 0.25 * double(job)}});
  return shard;
}

std::vector<std::string> write_toy_shards(const fs::path& dir, std::size_t jobs, int count) {
  std::vector<std::string> paths;
  for (int i = 0; i < count; ++i) {
    paths.push_back((dir / shard_file_name({i, count})).string());
    write_shard(paths.back(), toy_shard(jobs, i, count));
  }
  return paths;
}

std::vector<std::uint8_t> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// The InputError `call` throws; fails the test when it throws none.
template <class Call>
std::string refusal(Call call) {
  try {
    call();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(ShardFile, ThreeShardsMergeBackToEveryRecordInJobOrder) {
  const fs::path dir = scratch();
  std::vector<std::string> paths = write_toy_shards(dir, 23, 3);
  std::reverse(paths.begin(), paths.end());  // the files' order does not matter
  const MergedShards merged = merge_shards(paths);
  EXPECT_EQ(merged.fingerprint, "f00d");
  EXPECT_EQ(merged.study, kStudy);
  EXPECT_EQ(merged.shard_count, 3u);
  ASSERT_EQ(merged.results.size(), 23u);
  const std::vector<int> owners = assign_jobs(test::toy_costs(23), 3);
  for (std::size_t job = 0; job < 23; ++job) {
    const JobResult& result = merged.results[job];
    EXPECT_EQ(result.job, job);
    EXPECT_TRUE(result.record == test::toy_record(job)) << "job " << job;
    EXPECT_EQ(result.origin.rank, owners[job]);
    EXPECT_EQ(result.origin.host, "node" + std::to_string(owners[job]));
    EXPECT_EQ(result.origin.cuda_device, 1);
    EXPECT_EQ(result.origin.seconds, 0.25 * double(job));
  }
}

TEST(ShardFile, AShardWithNoJobsMergesToo) {
  // More shards than jobs: some have none, and still say which study they belong to.
  const fs::path dir = scratch();
  const MergedShards merged = merge_shards(write_toy_shards(dir, 3, 5));
  ASSERT_EQ(merged.results.size(), 3u);
  for (std::size_t job = 0; job < 3; ++job) EXPECT_TRUE(merged.results[job].record == test::toy_record(job));
  EXPECT_TRUE(read_shard((dir / shard_file_name({4, 5})).string()).results.empty());
}

TEST(ShardFile, AShardOfAnotherStudyIsRefusedNamingBothFiles) {
  const fs::path dir = scratch();
  std::vector<std::string> paths = write_toy_shards(dir, 10, 2);
  write_shard(paths[1], toy_shard(10, 1, 2, "beef"));
  const std::string message = refusal([&] { merge_shards(paths); });
  EXPECT_TRUE(has(message, paths[1] + ": a shard of another study than '" + paths[0] + "' (fingerprint beef, not f00d)"))
      << message;

  ShardContents other = toy_shard(10, 1, 2);
  other.study.push_back(0);
  write_shard(paths[1], other);
  EXPECT_TRUE(has(refusal([&] { merge_shards(paths); }), paths[1] + ": its study's description differs"));
}

TEST(ShardFile, ShardsOfAnotherSplitAreRefused) {
  const fs::path dir = scratch();
  const std::vector<std::string> three = write_toy_shards(dir, 10, 3);
  const std::string four = (dir / "four.bleedshard").string();
  write_shard(four, toy_shard(10, 3, 4));
  EXPECT_TRUE(has(refusal([&] { merge_shards({three[0], three[1], three[2], four}); }),
                  four + ": shard 3/4 of 10 jobs does not belong with '" + three[0] + "', one of 3 shards of 10 jobs"));
  write_shard(four, toy_shard(11, 2, 3));
  EXPECT_TRUE(has(refusal([&] { merge_shards({three[0], three[1], four}); }), "shard 2/3 of 11 jobs does not belong"));
}

TEST(ShardFile, AShardGivenTwiceOrMissingIsRefused) {
  const fs::path dir = scratch();
  const std::vector<std::string> paths = write_toy_shards(dir, 10, 3);
  const std::string copy = (dir / "copy.bleedshard").string();
  fs::copy_file(paths[1], copy);
  EXPECT_TRUE(has(refusal([&] { merge_shards({paths[0], paths[1], copy, paths[2]}); }),
                  copy + ": shard 1/3 again: '" + paths[1] + "' is that shard too"));
  EXPECT_TRUE(has(refusal([&] { merge_shards({paths[0], paths[2]}); }),
                  "shard 1/3 is missing: none of the 2 files given is that shard"));
  EXPECT_TRUE(has(refusal([&] { merge_shards({}); }), "no shard files to merge"));
}

TEST(ShardFile, AJobInTwoShardsOrInNoneIsRefused) {
  // Shards a bug (or a hand) filled with the wrong jobs: each shard is whole, the set is not.
  const fs::path dir = scratch();
  const std::vector<std::string> paths = write_toy_shards(dir, 10, 2);
  ShardContents second = toy_shard(10, 1, 2);
  const std::size_t taken = toy_shard(10, 0, 2).results.front().job;
  second.results.push_back(JobResult{taken, {1, 2}, {}});
  std::sort(second.results.begin(), second.results.end(), [](const JobResult& a, const JobResult& b) { return a.job < b.job; });
  write_shard(paths[1], second);
  EXPECT_TRUE(has(refusal([&] { merge_shards(paths); }), "job " + std::to_string(taken) + " is also in '"));

  second = toy_shard(10, 1, 2);
  const std::size_t dropped = second.results[1].job;
  second.results.erase(second.results.begin() + 1);
  write_shard(paths[1], second);
  EXPECT_TRUE(has(refusal([&] { merge_shards(paths); }), "job " + std::to_string(dropped) + " is in none of the shard files"));
  // The last job dropped: no later job shows the gap.
  second = toy_shard(10, 1, 2);
  ShardContents first = toy_shard(10, 0, 2);
  (first.results.back().job == 9 ? first : second).results.pop_back();
  write_shard(paths[0], first);
  write_shard(paths[1], second);
  EXPECT_TRUE(has(refusal([&] { merge_shards(paths); }), "job 9 is in none of the shard files"));
}

TEST(ShardFile, EveryCutOfAFileIsRefusedNamingIt) {
  // A shard copied while it was written (or a disk that filled): every length short of whole.
  const fs::path dir = scratch();
  ShardContents shard{"f00d", kStudy, 4, {0, 1}, {}};
  for (std::size_t job = 0; job < 4; ++job) shard.results.push_back(JobResult{job, {std::uint8_t(job), 9, 9}, {0, "h", -1, 1.0}});
  const std::string path = (dir / "whole.bleedshard").string();
  write_shard(path, shard);
  const std::vector<std::uint8_t> whole = file_bytes(path);
  const std::string cut = (dir / "cut.bleedshard").string();
  for (std::size_t size = 0; size < whole.size(); ++size) {
    write_bytes(cut, std::vector<std::uint8_t>(whole.begin(), whole.begin() + std::ptrdiff_t(size)));
    const std::string message = refusal([&] { read_shard(cut); });
    EXPECT_TRUE(has(message, cut + ": ")) << message;
    if (size < 8) {
      EXPECT_TRUE(has(message, "not a bleedsim shard file")) << message;
    } else if (size < 28) {
      EXPECT_TRUE(has(message, "is cut off: " + std::to_string(size) + " bytes, too few for a shard")) << message;
    } else {
      EXPECT_TRUE(has(message, "is cut off: " + std::to_string(size) + " of its " + std::to_string(whole.size()) + " bytes"))
          << message;
    }
  }
  write_bytes(cut, whole);
  EXPECT_EQ(read_shard(cut).results.size(), 4u);
}

TEST(ShardFile, EveryDamagedByteIsRefusedNamingTheFile) {
  const fs::path dir = scratch();
  ShardContents shard{"f00d", kStudy, 3, {1, 2}, {}};
  for (std::size_t job = 0; job < 3; ++job) shard.results.push_back(JobResult{job, {std::uint8_t(job), 7}, {1, "h", 0, 2.0}});
  const std::string path = (dir / "whole.bleedshard").string();
  write_shard(path, shard);
  const std::vector<std::uint8_t> whole = file_bytes(path);
  const std::string damaged = (dir / "damaged.bleedshard").string();
  for (std::size_t at = 0; at < whole.size(); ++at) {
    std::vector<std::uint8_t> bytes = whole;
    bytes[at] ^= 0x10;
    write_bytes(damaged, bytes);
    EXPECT_TRUE(has(refusal([&] { read_shard(damaged); }), damaged + ": ")) << "byte " << at;
  }
  // What some of them say: the version, the checksum, and a byte too many.
  std::vector<std::uint8_t> bytes = whole;
  bytes[8] = 2;
  write_bytes(damaged, bytes);
  EXPECT_TRUE(has(refusal([&] { read_shard(damaged); }), "a shard file of format version 2; this bleedsim reads version 1"));
  bytes = whole;
  bytes[40] ^= 1;
  write_bytes(damaged, bytes);
  EXPECT_TRUE(has(refusal([&] { read_shard(damaged); }), "is damaged: its checksum does not match its contents"));
  bytes = whole;
  bytes.push_back(0);
  write_bytes(damaged, bytes);
  EXPECT_TRUE(has(refusal([&] { read_shard(damaged); }), "is damaged: 1 bytes more than the"));
}

// The shard fuzzer's find (fuzz/regressions/shard_fuzzer/): a damaged result count, in a file whose
// checksum was made to fit it, was allocated for before any job was read: std::length_error, or
// gigabytes, where the file holds five jobs. A count is checked against the bytes left first.
TEST(ShardFile, AResultCountPastWhatTheFileCanHoldIsRefused) {
  const fs::path dir = scratch();
  const std::string path = (dir / "counted.bleedshard").string();
  write_shard(path, toy_shard(5, 0, 1));
  const std::vector<std::uint8_t> whole = file_bytes(path);
  // After the prologue (20 bytes): the fingerprint "f00d" and the study, each after its length, the
  // job count, the shard's i and K, then the count; and at the end, the checksum of all before it.
  const std::size_t count_at = 20 + 8 + 4 + 8 + kStudy.size() + 8 + 4 + 4, checksum_at = whole.size() - 8;
  const auto put = [](std::vector<std::uint8_t>& bytes, std::size_t at, std::uint64_t v) {
    for (int i = 0; i < 8; ++i) bytes[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
  };
  for (const std::uint64_t count : {std::uint64_t(1) << 60, ~std::uint64_t(0)}) {
    std::vector<std::uint8_t> bytes = whole;
    put(bytes, count_at, count);
    put(bytes, checksum_at, fnv1a64(bytes.data(), checksum_at));
    const std::string message = refusal([&] { decode_shard(bytes, path); });
    EXPECT_TRUE(has(message, path + ": the shard file is damaged: the result count is " + std::to_string(count) +
                                 " at byte " + std::to_string(count_at + 8) + ", but the "))
        << message;
  }
}

TEST(ShardFile, AFileThatIsNotAShardIsRefused) {
  const fs::path dir = scratch();
  const std::string text = (dir / "notes.txt").string();
  std::ofstream(text) << "shard 0 of 3, done\n";
  EXPECT_TRUE(has(refusal([&] { read_shard(text); }), text + ": not a bleedsim shard file"));
  const std::string missing = (dir / "missing.bleedshard").string();
  EXPECT_TRUE(
      has(refusal([&] { read_shard(missing); }), missing + ": cannot read shard file: No such file or directory"));
  EXPECT_TRUE(has(refusal([&] { read_shard(dir.string()); }),
                  dir.string() + ": cannot read shard file: it is a directory, not a regular file"));
}

TEST(ShardFile, AWriteReplacesTheFileWholeOrLeavesNothing) {
  const fs::path dir = scratch();
  const std::string path = (dir / shard_file_name({0, 2})).string();
  write_shard(path, toy_shard(6, 0, 2));
  // A task of a job array run again replaces its shard.
  write_shard(path, toy_shard(6, 0, 2, "cafe"));
  EXPECT_EQ(read_shard(path).fingerprint, "cafe");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << "a temporary file was left";

  const std::string nowhere = (dir / "no-such-folder" / "shard.bleedshard").string();
  try {
    write_shard(nowhere, toy_shard(6, 1, 2));
    ADD_FAILURE() << "written into a folder that is not there";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write shard file '" + nowhere + "': No such file or directory");
  }
  ShardContents unordered = toy_shard(6, 1, 2);
  std::swap(unordered.results.front(), unordered.results.back());
  EXPECT_THROW(write_shard(path, unordered), std::invalid_argument);
  EXPECT_EQ(read_shard(path).fingerprint, "cafe");
}

TEST(ShardId, ReadsIOfKAndRefusesTheRestNamingTheOption) {
  EXPECT_EQ(parse_shard("0/1").count, 1);
  EXPECT_EQ(parse_shard("7/8").index, 7);
  for (const char* bad : {"", "3", "3/", "/3", "a/3", "-1/3", "1/3x", "1/-3", "1.0/3", "1 /3"}) {
    const std::string message = refusal([&] { parse_shard(bad); });
    EXPECT_TRUE(has(message, "--shard: write it as i/K")) << bad << ": " << message;
  }
  EXPECT_TRUE(has(refusal([] { parse_shard("3/3"); }), "--shard: i counts from 0, so it must be below K: 3/3 has no shard 3 (the last is 2/3)"));
  EXPECT_TRUE(has(refusal([] { parse_shard("0/0"); }), "--shard: K must be from 1 to 1000000"));
  EXPECT_TRUE(has(refusal([] { parse_shard("0/99999999"); }), "--shard: write it as i/K"));
  EXPECT_EQ(shard_file_name({2, 8}), "shard-2-of-8.bleedshard");
  EXPECT_EQ(shard_file_name({2, 12}), "shard-02-of-12.bleedshard");
}

}  // namespace
}  // namespace bleedsim
