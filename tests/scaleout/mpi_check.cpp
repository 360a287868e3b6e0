// The distribution layer over real MPI ranks, driven by tests/scaleout/mpi_check.py (which runs it
// under mpirun and compares the files it writes). Modes:
//   run OUT          every toy job over the ranks; rank 0 checks each record against the job that
//                    made it and writes them all to OUT, in job order (a dump to compare byte for byte);
//   fail             the last rank's first job throws after 0.5 s while rank 0's jobs take 0.3 s each:
//                    every rank must end with exit 1, rank 0 printing the failure, and rank 0 must
//                    stop after the job it was running then, not run all of its own;
//   refuse           rank 0 finds its output unwritable before the jobs (Ranks::all_ok): every rank
//                    must end with exit 2 without running a job;
//   shard i/K DIR    the shard's jobs over the ranks; rank 0 writes DIR/<shard file name>;
//   merge DIR OUT    every shard file in DIR merged, then written to OUT as `run` writes it.
// Each rank says on stderr how it ended ("rank 1 of 2: exit 1 after 0 of its 11 jobs").
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "core/scaleout/job_assignment.h"
#include "core/scaleout/run_jobs.h"
#include "core/scaleout/shard_file.h"
#include "tests/scaleout/toy_jobs.h"

namespace {

using namespace bleedsim;
namespace fs = std::filesystem;

constexpr std::size_t kJobs = 23;
// Small pieces, so the 3 MiB records go as 48 messages each: the path a record past 2 GiB takes.
const RunJobsOptions kOptions{65536};

// Every record, checked against its job, in job order as (job, length, bytes) in little-endian u64s.
bool write_dump(const std::string& path, const std::vector<JobResult>& results) {
  std::ofstream out(path, std::ios::binary);
  for (std::size_t i = 0; i < results.size(); ++i) {
    const JobResult& result = results[i];
    if (result.job != i || result.record != test::toy_record(i)) {
      std::fprintf(stderr, "mpi_check: the result at place %zu is job %zu, whose record is not the toy job's\n", i,
                   result.job);
      return false;
    }
    ByteWriter label;
    label.u64(result.job);
    label.u64(result.record.size());
    out.write(reinterpret_cast<const char*>(label.data().data()), std::streamsize(label.data().size()));
    out.write(reinterpret_cast<const char*>(result.record.data()), std::streamsize(result.record.size()));
  }
  return bool(out);
}

int run_mode(const Ranks& ranks, const std::string& out) {
  const std::vector<double> costs = test::toy_costs(kJobs);
  const std::vector<JobResult> results =
      run_jobs(ranks, costs, [](std::size_t job) { return test::toy_record(job); }, kOptions);
  if (!ranks.is_root()) return results.empty() ? 0 : 1;
  // Each job ran on the rank assign_jobs gave it.
  const std::vector<int> owners = assign_jobs(costs, ranks.size());
  std::map<int, std::pair<const JobOrigin*, int>> used;  // rank: where it ran, and how many jobs
  for (const JobResult& result : results) {
    used.emplace(result.origin.rank, std::make_pair(&result.origin, 0)).first->second.second++;
    if (result.job < owners.size() && result.origin.rank != owners[result.job]) {
      std::fprintf(stderr, "mpi_check: job %zu ran on rank %d, not on rank %d\n", result.job, result.origin.rank,
                   owners[result.job]);
      return 1;
    }
  }
  if (results.size() != kJobs || !write_dump(out, results)) return 1;
  std::printf("mpi_check: %zu jobs gathered from %zu of %d ranks (%s)\n", results.size(), used.size(), ranks.size(),
              Ranks::mpi_library().empty() ? "no MPI in this build" : Ranks::mpi_library().c_str());
  for (const auto& [rank, where] : used)
    std::printf("mpi_check: rank %d on host %s, CUDA device %d: %d jobs\n", rank, where.first->host.c_str(),
                where.first->cuda_device, where.second);
  return 0;
}

int fail_mode(const Ranks& ranks) {
  const std::vector<double> costs = test::toy_costs(kJobs);
  const std::vector<int> owners = assign_jobs(costs, ranks.size());
  // The first job of the last rank fails (rank 1 of 2).
  const std::size_t failing = jobs_of_part(owners, ranks.size() - 1).front();
  const std::size_t mine = jobs_of_part(owners, ranks.rank()).size();
  std::size_t ran = 0;
  int code = 0;
  try {
    run_jobs(ranks, costs, [&](std::size_t job) {
      ++ran;
      if (job == failing) {
        // Late enough that rank 0 is in the middle of its own jobs when it hears.
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
        throw std::runtime_error("toy job " + std::to_string(job) + " refused on purpose");
      }
      // Rank 0's jobs take long enough (0.3 s each) that, had it not heard of the failure, it would show.
      if (ranks.rank() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(300));
      return test::toy_record(job);
    }, kOptions);
  } catch (const JobFailed& e) {
    if (ranks.is_root()) std::fprintf(stderr, "mpi_check: %s\n", e.what());
    code = 1;
  }
  std::fprintf(stderr, "rank %d of %d: exit %d after %zu of its %zu jobs\n", ranks.rank(), ranks.size(), code, ran, mine);
  return code;
}

int refuse_mode(const Ranks& ranks) {
  // As a command whose rank 0 finds its output folder in use: only rank 0 knows.
  const bool ready = !ranks.is_root();
  std::size_t ran = 0;
  if (ranks.all_ok(ready))
    run_jobs(ranks, test::toy_costs(kJobs), [&](std::size_t job) {
      ++ran;
      return test::toy_record(job);
    }, kOptions);
  std::fprintf(stderr, "rank %d of %d: exit 2 after %zu jobs\n", ranks.rank(), ranks.size(), ran);
  return 2;
}

int shard_mode(const Ranks& ranks, const std::string& which, const std::string& dir) {
  const ShardId shard = parse_shard(which);
  const std::vector<double> costs = test::toy_costs(kJobs);
  const std::vector<std::size_t> jobs = jobs_of_part(assign_jobs(costs, shard.count), shard.index);
  std::vector<JobResult> results =
      run_jobs(ranks, costs, jobs, [](std::size_t job) { return test::toy_record(job); }, kOptions);
  if (!ranks.is_root()) return 0;
  write_shard((fs::path(dir) / shard_file_name(shard)).string(),
              ShardContents{"toy-study", {'t', 'o', 'y'}, kJobs, shard, std::move(results)});
  return 0;
}

int merge_mode(const std::string& dir, const std::string& out) {
  std::vector<std::string> paths;
  for (const auto& entry : fs::directory_iterator(dir)) paths.push_back(entry.path().string());
  const MergedShards merged = merge_shards(paths);
  if (merged.fingerprint != "toy-study" || merged.results.size() != kJobs || !write_dump(out, merged.results)) return 1;
  std::printf("mpi_check: %zu jobs merged from %zu shard files\n", merged.results.size(), paths.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  const std::string mode = args.empty() ? "" : args[0];
  int code = 2;
  {
    // Held until every rank has its exit code: its end (MPI_Finalize) waits for them all.
    const Ranks ranks;
    try {
      if (mode == "run" && args.size() == 2) code = run_mode(ranks, args[1]);
      else if (mode == "fail" && args.size() == 1) code = fail_mode(ranks);
      else if (mode == "refuse" && args.size() == 1) code = refuse_mode(ranks);
      else if (mode == "shard" && args.size() == 3) code = shard_mode(ranks, args[1], args[2]);
      else if (mode == "merge" && args.size() == 3 && ranks.size() == 1) code = merge_mode(args[1], args[2]);
      else std::fprintf(stderr, "usage: mpi_check run OUT | fail | refuse | shard i/K DIR | merge DIR OUT (one rank)\n");
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mpi_check: rank %d: %s\n", ranks.rank(), e.what());
      code = 1;
    }
  }
  return code;
}
