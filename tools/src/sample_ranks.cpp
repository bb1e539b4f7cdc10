#include "sample_ranks.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "rockfit/core/errors.hpp"

#ifdef ROCKFIT_WITH_MPI
#include <mpi.h>
#endif

namespace rockfit::tools {
namespace {

int EnvInt(const char* name) {
  const char* value = std::getenv(name);
  if (value == nullptr || *value == '\0') return 0;
  return std::atoi(value);
}

}  // namespace

bool BuiltWithMpi() {
#ifdef ROCKFIT_WITH_MPI
  return true;
#else
  return false;
#endif
}

int LauncherWorldSize() {
  // Open MPI's mpirun, MPICH/Hydra and Slurm's PMI-2.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    if (const int n = EnvInt(name); n > 0) return n;
  }
  // srun --mpi=pmix: PMIx names the rank; Slurm the number of tasks.
  if (std::getenv("PMIX_RANK") != nullptr) return std::max(1, EnvInt("SLURM_NTASKS"));
  return 1;
}

bool StartedByLauncher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMI_RANK", "PMIX_RANK"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

SampleRanks::SampleRanks(bool use_mpi) {
#ifdef ROCKFIT_WITH_MPI
  if (!use_mpi) return;
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  }
  mpi_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
#else
  const int launched = LauncherWorldSize();
  if (use_mpi || launched > 1) {
    throw InvalidArgument(
        std::string("this rockfit was built without MPI") +
        (launched > 1 ? ", but " + std::to_string(launched) + " copies of it were started by mpirun or srun: each would "
                        "run the whole study and write the same file"
                      : "") +
        ". Install Open MPI (apt-get install libopenmpi-dev openmpi-bin), configure with -DROCKFIT_WITH_MPI=ON and "
        "build again; or run one process, which uses every core through its threads (-j)");
  }
#endif
}

SampleRanks::~SampleRanks() {
#ifdef ROCKFIT_WITH_MPI
  if (mpi_) {
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (!finalised) MPI_Finalize();
  }
#endif
}

bool SampleRanks::AllOk(bool ok) const {
#ifdef ROCKFIT_WITH_MPI
  if (mpi_) {
    int local = ok ? 1 : 0, all = 0;
    MPI_Allreduce(&local, &all, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
    return all != 0;
  }
#endif
  return ok;
}

std::vector<std::int64_t> SampleRanks::Broadcast(std::vector<std::int64_t> values) const {
#ifdef ROCKFIT_WITH_MPI
  if (mpi_) {
    long long n = static_cast<long long>(values.size());
    MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
    values.resize(static_cast<std::size_t>(n));
    // In pieces: MPI counts are int.
    constexpr std::size_t kPiece = 1u << 26;
    for (std::size_t at = 0; at < values.size(); at += kPiece) {
      const int count = static_cast<int>(std::min(kPiece, values.size() - at));
      MPI_Bcast(values.data() + at, count, MPI_INT64_T, 0, MPI_COMM_WORLD);
    }
  }
#endif
  return values;
}

std::vector<quake::SampleOutcome> SampleRanks::Gather(const std::vector<quake::SampleOutcome>& local) const {
#ifdef ROCKFIT_WITH_MPI
  if (mpi_) {
    constexpr int kRecord = static_cast<int>(sizeof(quake::SampleOutcome));
    const int bytes = static_cast<int>(local.size()) * kRecord;
    std::vector<int> counts(rank_ == 0 ? size_ : 0), displacements(rank_ == 0 ? size_ : 0);
    MPI_Gather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::vector<quake::SampleOutcome> all;
    if (rank_ == 0) {
      int total = 0;
      for (int r = 0; r < size_; ++r) {
        displacements[static_cast<std::size_t>(r)] = total;
        total += counts[static_cast<std::size_t>(r)];
      }
      all.resize(static_cast<std::size_t>(total / kRecord));
    }
    MPI_Gatherv(local.data(), bytes, MPI_BYTE, all.data(), counts.data(), displacements.data(), MPI_BYTE, 0,
                MPI_COMM_WORLD);
    return all;
  }
#endif
  return local;
}

void SampleRanks::Abort(int code) const {
  std::cerr << std::flush;
#ifdef ROCKFIT_WITH_MPI
  if (mpi_ && size_ > 1) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

}  // namespace rockfit::tools
