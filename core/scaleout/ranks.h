#pragma once
// The processes a study is spread over: the MPI ranks that mpirun (or srun) started, or this
// process alone. Hold one Ranks for the whole of a command that spreads jobs (it starts MPI and
// ends it), on the thread that calls run_jobs: MPI is asked for MPI_THREAD_FUNNELED, so only that
// thread may talk to the other ranks (worker threads inside a job are fine).
#include <string>

namespace bleedsim {

class Ranks {
 public:
  // Joins the MPI job when this build has MPI and a launcher started the process (its environment
  // names a rank: OMPI_COMM_WORLD_SIZE, PMIX_RANK or PMI_RANK); otherwise this process alone is
  // rank 0 of 1 and MPI is left untouched, so a plain `bleedsim study` never starts MPI's runtime.
  // MPI already started by the host is joined and left running. Throws std::logic_error once MPI
  // has ended in this process (it starts once per process: hold one Ranks, not one after another).
  // with_cuda false (a study of the CPU backend alone): no rank asks CUDA for its devices, which
  // starts the driver in every rank for nothing, and cuda_device() is -1.
  explicit Ranks(bool with_cuda = true);
  // Ends MPI when this Ranks started it. Every rank must get here: MPI_Finalize waits for them all.
  ~Ranks();
  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // Rank 0 gathers the results and alone writes output.
  bool is_root() const { return rank_ == 0; }
  // This rank's place among the ranks on its host (MPI_COMM_TYPE_SHARED).
  int local_rank() const { return local_rank_; }
  const std::string& host() const { return host_; }
  // The CUDA device for this rank's jobs: its local rank modulo the devices this process sees
  // (after CUDA_VISIBLE_DEVICES); -1 when it sees none or was made without CUDA. Pass it on in
  // BackendChoice::cuda_device.
  int cuda_device() const { return cuda_device_; }

  // True when every rank passes true (a logical and over the ranks; call it on every rank). A check
  // only rank 0 makes, such as taking its output folder, must reach the others this way before the
  // jobs start: a rank 0 that simply threw would leave them waiting for it in run_jobs.
  bool all_ok(bool mine) const;

  // "Open MPI v4.1.4, ..." for `bleedsim info`; empty in a build without MPI.
  static std::string mpi_library();

 private:
  int rank_ = 0, size_ = 1, local_rank_ = 0;
  std::string host_;
  int cuda_device_ = -1;
  bool started_mpi_ = false;
};

}  // namespace bleedsim
