// run_jobs over MPI ranks. The protocol, every message on MPI_COMM_WORLD:
//   1. Each rank runs its jobs in ascending order. Before each it looks for a STOP message; a rank
//      whose job throws sends STOP to every other rank at once and runs nothing more, so a failure
//      ends the run after the jobs already running, not after every rank's whole list.
//   2. Each rank other than 0 sends rank 0 its REPORT: a length-prefixed manifest (status, the
//      failure if any, each result's job, origin and record length), then each record's bytes in
//      pieces of at most max_message_bytes (an MPI count is an int). A rank that failed or stopped
//      sends no records. Rank 0 takes the reports in rank order; messages between two ranks on one
//      tag arrive in the order sent, so no piece needs a label.
//   3. Rank 0 broadcasts the OUTCOME: the ranks that failed, and the failure with the lowest job.
//   4. Each rank receives one STOP from every failed rank but itself (they know now how many to
//      expect), and each failed rank waits for its STOP sends: no message is left unmatched at
//      MPI_Finalize. Then, on every rank alike, a failure is thrown as JobFailed.
// A fault outside the jobs (memory for a record, a broken message) cannot be reported in order:
// that rank prints it and calls MPI_Abort, which ends every rank, so nothing hangs. (An MPI error
// ends every rank by itself: MPI_COMM_WORLD's handler is MPI_ERRORS_ARE_FATAL.)
#include "core/scaleout/mpi_exchange.h"

#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <stdexcept>

#include "core/scaleout/byte_codec.h"
#include "core/scaleout/job_attempt.h"

namespace bleedsim {
namespace {

constexpr int kTagStop = 1;
constexpr int kTagReport = 2;

enum class Status : std::uint32_t { ran_all = 0, failed = 1, stopped = 2 };

// `size` bytes in pieces of at most `piece` (the receiver knows `size` already).
void send_bytes(const std::uint8_t* data, std::size_t size, int to, std::size_t piece) {
  for (std::size_t at = 0; at < size; at += piece)
    MPI_Send(data + at, int(std::min(piece, size - at)), MPI_BYTE, to, kTagReport, MPI_COMM_WORLD);
}

void receive_bytes(std::uint8_t* data, std::size_t size, int from, std::size_t piece) {
  for (std::size_t at = 0; at < size; at += piece)
    MPI_Recv(data + at, int(std::min(piece, size - at)), MPI_BYTE, from, kTagReport, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
}

// A message whose length goes first.
void send_message(const std::vector<std::uint8_t>& bytes, int to, std::size_t piece) {
  const std::uint64_t size = bytes.size();
  MPI_Send(&size, 1, MPI_UINT64_T, to, kTagReport, MPI_COMM_WORLD);
  send_bytes(bytes.data(), bytes.size(), to, piece);
}

std::vector<std::uint8_t> receive_message(int from, std::size_t piece) {
  std::uint64_t size = 0;
  MPI_Recv(&size, 1, MPI_UINT64_T, from, kTagReport, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  std::vector<std::uint8_t> bytes(size);
  receive_bytes(bytes.data(), bytes.size(), from, piece);
  return bytes;
}

// Rank 0's `bytes` on every rank.
std::vector<std::uint8_t> broadcast_message(std::vector<std::uint8_t> bytes, std::size_t piece) {
  std::uint64_t size = bytes.size();
  MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  bytes.resize(size);
  for (std::size_t at = 0; at < size; at += piece)
    MPI_Bcast(bytes.data() + at, int(std::min(piece, std::size_t(size) - at)), MPI_BYTE, 0, MPI_COMM_WORLD);
  return bytes;
}

bool stop_arrived() {
  int arrived = 0;
  MPI_Iprobe(MPI_ANY_SOURCE, kTagStop, MPI_COMM_WORLD, &arrived, MPI_STATUS_IGNORE);
  return arrived != 0;
}

// One rank's jobs, as its report will tell them.
struct RankWork {
  Status status = Status::ran_all;
  JobAttempt failure;                // when failed
  std::vector<JobResult> results;    // when ran_all
  std::vector<MPI_Request> stops;    // the STOP messages this rank sent
};

RankWork run_own_jobs(const Ranks& ranks, const std::vector<std::size_t>& jobs, const std::vector<int>& owners,
                      const JobFunction& run) {
  RankWork work;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (owners[i] != ranks.rank()) continue;
    if (stop_arrived()) {
      work.status = Status::stopped;
      break;
    }
    JobAttempt attempt = attempt_job(ranks, jobs[i], run);
    if (attempt.failed) {
      work.status = Status::failed;
      work.failure = std::move(attempt);
      for (int r = 0; r < ranks.size(); ++r) {
        if (r == ranks.rank()) continue;
        work.stops.emplace_back();
        MPI_Isend(nullptr, 0, MPI_BYTE, r, kTagStop, MPI_COMM_WORLD, &work.stops.back());
      }
      break;
    }
    work.results.push_back(std::move(attempt.result));
  }
  if (work.status != Status::ran_all) work.results.clear();  // the run fails: its records are not needed
  return work;
}

std::vector<std::uint8_t> manifest_of(const RankWork& work) {
  ByteWriter out;
  out.u32(std::uint32_t(work.status));
  if (work.status == Status::failed) {
    out.u64(work.failure.result.job);
    write_origin(out, work.failure.result.origin);
    out.text(work.failure.error);
  }
  out.u64(work.results.size());
  for (const JobResult& result : work.results) {
    out.u64(result.job);
    write_origin(out, result.origin);
    out.u64(result.record.size());
  }
  return out.take();
}

// Rank r's work as its report tells it, its records received into place.
RankWork receive_report(int from, std::size_t piece) {
  const std::vector<std::uint8_t> manifest = receive_message(from, piece);
  ByteReader in(manifest.data(), manifest.size());
  const std::string who = "rank " + std::to_string(from) + "'s report";
  RankWork work;
  work.status = Status(in.u32(who + "'s status"));
  if (work.status == Status::failed) {
    work.failure.failed = true;
    work.failure.result.job = in.u64(who + "'s failed job");
    work.failure.result.origin = read_origin(in, who + "'s failed job");
    work.failure.error = in.text(who + "'s failure");
  }
  work.results.resize(in.u64(who + "'s result count"));
  for (JobResult& result : work.results) {
    result.job = in.u64(who + "'s job");
    result.origin = read_origin(in, who + "'s job " + std::to_string(result.job));
    result.record.resize(in.u64(who + "'s job " + std::to_string(result.job) + " length"));
  }
  for (JobResult& result : work.results) receive_bytes(result.record.data(), result.record.size(), from, piece);
  return work;
}

// Rank 0's verdict: the ranks that failed, and the failure with the lowest job among them.
struct Outcome {
  std::vector<int> failed_ranks;
  JobAttempt first;
};

std::vector<std::uint8_t> encode(const Outcome& outcome) {
  ByteWriter out;
  out.u32(std::uint32_t(outcome.failed_ranks.size()));
  for (const int r : outcome.failed_ranks) out.i32(r);
  if (!outcome.failed_ranks.empty()) {
    out.u64(outcome.first.result.job);
    write_origin(out, outcome.first.result.origin);
    out.text(outcome.first.error);
  }
  return out.take();
}

Outcome decode(const std::vector<std::uint8_t>& bytes) {
  ByteReader in(bytes.data(), bytes.size());
  Outcome outcome;
  outcome.failed_ranks.resize(in.u32("the outcome's failed rank count"));
  for (int& r : outcome.failed_ranks) r = in.i32("a failed rank");
  if (!outcome.failed_ranks.empty()) {
    outcome.first.result.job = in.u64("the failed job");
    outcome.first.result.origin = read_origin(in, "the failed job");
    outcome.first.error = in.text("the failure");
  }
  return outcome;
}

// Rank 0: every rank's report, mine first; the records in the order of `jobs`.
Outcome gather(const Ranks& ranks, RankWork mine, const std::vector<std::size_t>& jobs, std::size_t piece,
               std::vector<JobResult>& results) {
  Outcome outcome;
  std::vector<bool> filled(jobs.size(), false);
  for (int r = 0; r < ranks.size(); ++r) {
    RankWork work = r == 0 ? std::move(mine) : receive_report(r, piece);
    if (work.status == Status::failed) {
      if (outcome.failed_ranks.empty() || work.failure.result.job < outcome.first.result.job)
        outcome.first = work.failure;
      outcome.failed_ranks.push_back(r);
    }
    for (JobResult& result : work.results) {
      const auto at = std::lower_bound(jobs.begin(), jobs.end(), result.job);
      if (at == jobs.end() || *at != result.job || filled[std::size_t(at - jobs.begin())])
        throw std::logic_error("rank " + std::to_string(r) + " sent job " + std::to_string(result.job) +
                               ", which is not one of its own or came twice");
      filled[std::size_t(at - jobs.begin())] = true;
      results[std::size_t(at - jobs.begin())] = std::move(result);
    }
  }
  if (outcome.failed_ranks.empty() && std::find(filled.begin(), filled.end(), false) != filled.end())
    throw std::logic_error("every rank ran all its jobs, yet a job's record is missing");
  return outcome;
}

}  // namespace

std::vector<JobResult> run_jobs_over_mpi(const Ranks& ranks, const std::vector<std::size_t>& jobs,
                                         const std::vector<int>& owners, const JobFunction& run,
                                         const RunJobsOptions& options) {
  std::vector<JobResult> results;
  Outcome outcome;
  try {
    RankWork mine = run_own_jobs(ranks, jobs, owners, run);
    std::vector<MPI_Request> stops = std::move(mine.stops);
    const std::size_t piece = options.max_message_bytes;
    std::vector<std::uint8_t> verdict;
    if (ranks.is_root()) {
      results.resize(jobs.size());
      outcome = gather(ranks, std::move(mine), jobs, piece, results);
      verdict = encode(outcome);
    } else {
      send_message(manifest_of(mine), 0, piece);
      for (const JobResult& result : mine.results) send_bytes(result.record.data(), result.record.size(), 0, piece);
    }
    outcome = decode(broadcast_message(std::move(verdict), piece));
    for (const int r : outcome.failed_ranks)
      if (r != ranks.rank()) MPI_Recv(nullptr, 0, MPI_BYTE, r, kTagStop, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Waitall(int(stops.size()), stops.data(), MPI_STATUSES_IGNORE);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bleedsim: rank %d: spreading the jobs failed outside them: %s; ending every rank\n",
                 ranks.rank(), e.what());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  if (!outcome.failed_ranks.empty())
    throw JobFailed(outcome.first.result.job, outcome.first.result.origin, ranks.size(), outcome.first.error,
                    int(outcome.failed_ranks.size()) - 1);
  return results;
}

}  // namespace bleedsim
