// The processes that share a sample study (`rockfit fragility`): this process alone, or the ranks of
// MPI_COMM_WORLD when rockfit is built with MPI (CMake option ROCKFIT_WITH_MPI) and started by mpirun or srun.
// Plain MPI C API, MPI_THREAD_FUNNELED: only the main thread of each rank calls MPI; TBB threads only simulate.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rockfit/quake/fragility_study.hpp"

namespace rockfit::tools {

// Whether this rockfit was built with MPI.
bool BuiltWithMpi();
// The number of processes a launcher (mpirun, srun with PMI/PMIx) says this job has, from its environment; 1 when
// not started by one.
int LauncherWorldSize();
// Whether a launcher (mpirun, srun with PMI/PMIx) started this process, even as a job of one.
bool StartedByLauncher();

class SampleRanks {
 public:
  // Initialises MPI when `use_mpi` (MPI_Init_thread, FUNNELED); otherwise a single process. InvalidArgument when
  // MPI is asked for (`use_mpi`, or a launcher started several processes) and this build has none.
  explicit SampleRanks(bool use_mpi);
  ~SampleRanks();  // MPI_Finalize
  SampleRanks(const SampleRanks&) = delete;
  SampleRanks& operator=(const SampleRanks&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool mpi() const { return mpi_; }

  // True on every rank when `ok` is true on every rank (collective).
  bool AllOk(bool ok) const;
  // Rank 0's `values` on every rank (collective).
  std::vector<std::int64_t> Broadcast(std::vector<std::int64_t> values) const;
  // Every rank's `local` outcomes, concatenated in rank order, on rank 0; empty on the others (collective,
  // MPI_Gatherv of the fixed-size records as bytes: the ranks must share the byte layout, i.e. the same build).
  std::vector<quake::SampleOutcome> Gather(const std::vector<quake::SampleOutcome>& local) const;
  // Ends every rank with `code` after rank `rank()` printed why (MPI_Abort); a plain exit without MPI.
  [[noreturn]] void Abort(int code) const;

 private:
  bool mpi_ = false;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace rockfit::tools
