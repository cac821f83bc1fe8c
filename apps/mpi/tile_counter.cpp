#include "apps/mpi/tile_counter.h"

namespace snee {

TileCounter::TileCounter(MPI_Comm comm, std::mutex& mpi_mutex, uint64_t tiles_per_claim)
    : mpi_mutex_(mpi_mutex), tiles_per_claim_(tiles_per_claim) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  uint64_t* next = nullptr;
  const MPI_Aint bytes = rank == 0 ? sizeof(uint64_t) : 0;
  MPI_Win_allocate(bytes, sizeof(uint64_t), MPI_INFO_NULL, comm, &next, &window_);
  if (rank == 0) {
    // The window's memory starts undefined; a local store is well defined inside an epoch.
    MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, window_);
    *next = 0;
    MPI_Win_unlock(0, window_);
  }
  MPI_Barrier(comm);  // no claim before the counter is 0
  MPI_Win_lock_all(MPI_MODE_NOCHECK, window_);
}

TileCounter::~TileCounter() {
  MPI_Win_unlock_all(window_);
  MPI_Win_free(&window_);
}

TileRange TileCounter::claim() {
  const uint64_t add = tiles_per_claim_;
  uint64_t first = 0;
  {
    std::lock_guard<std::mutex> lock(mpi_mutex_);
    MPI_Fetch_and_op(&add, &first, MPI_UINT64_T, 0, 0, MPI_SUM, window_);
    MPI_Win_flush(0, window_);
  }
  return {first, first + tiles_per_claim_};
}

}  // namespace snee
