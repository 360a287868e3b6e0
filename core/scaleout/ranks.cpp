#include "core/scaleout/ranks.h"

#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <stdexcept>

#include "core/runtime/backend.h"

#if BLEEDSIM_HAVE_MPI
#include <mpi.h>
#endif

namespace bleedsim {
namespace {

std::string host_name() {
  char name[HOST_NAME_MAX + 1] = {};
  if (gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

#if BLEEDSIM_HAVE_MPI
// A launcher gives each process its rank in the environment: Open MPI's mpirun, PMIx launchers
// (srun --mpi=pmix, prterun) and PMI ones (srun --mpi=pmi2, MPICH's hydra). A process started
// without one is not initialised as an MPI singleton: Open MPI's would start a daemon for it.
bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}
#endif

}  // namespace

Ranks::Ranks(bool with_cuda) : host_(host_name()) {
#if BLEEDSIM_HAVE_MPI
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  if (finalised) throw std::logic_error("MPI has already ended in this process (an earlier Ranks ended it); it cannot start again");
  if (!initialised && launched_by_mpi()) {
    // FUNNELED: a job's worker threads never call MPI; only the thread holding Ranks does.
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    started_mpi_ = true;
    initialised = 1;
  }
  if (initialised) {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Comm host_ranks;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &host_ranks);
    MPI_Comm_rank(host_ranks, &local_rank_);
    MPI_Comm_free(&host_ranks);
  }
#endif
  const int devices = with_cuda ? cuda_device_count() : 0;
  cuda_device_ = devices > 0 ? local_rank_ % devices : -1;
}

Ranks::~Ranks() {
#if BLEEDSIM_HAVE_MPI
  if (started_mpi_) MPI_Finalize();
#endif
}

bool Ranks::all_ok(bool mine) const {
#if BLEEDSIM_HAVE_MPI
  if (size_ > 1) {
    int ok = mine ? 1 : 0, all = 0;
    MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
    return all != 0;
  }
#endif
  return mine;
}

std::string Ranks::mpi_library() {
#if BLEEDSIM_HAVE_MPI
  char text[MPI_MAX_LIBRARY_VERSION_STRING] = {};
  int length = 0;
  MPI_Get_library_version(text, &length);
  std::string version(text, std::size_t(length));
  // Open MPI's runs on over several lines (its repository and release date): the first says it.
  return version.substr(0, version.find_first_of("\r\n"));
#else
  return "";
#endif
}

}  // namespace bleedsim
