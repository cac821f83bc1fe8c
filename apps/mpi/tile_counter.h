// The shared counter from which the processes of a split render claim their tiles while they
// render (RenderHooks::tile_source): one integer in an MPI window on rank 0, advanced with
// MPI_Fetch_and_op under a passive-target lock held for the whole render, so rank 0 takes no
// part in a claim and renders with all its threads like the others.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <mutex>

#include "scheduler/render.h"

namespace snee {

class TileCounter {
 public:
  // Collective over `comm`. `mpi_mutex` serializes this process's MPI calls (the render threads
  // that claim and StopTogether's share it: MPI_THREAD_SERIALIZED). Claims hand out
  // `tiles_per_claim` tiles at a time.
  TileCounter(MPI_Comm comm, std::mutex& mpi_mutex, uint64_t tiles_per_claim);
  // Collective too (MPI_Win_free): only once every process is done claiming.
  ~TileCounter();
  TileCounter(const TileCounter&) = delete;
  TileCounter& operator=(const TileCounter&) = delete;

  // The next tiles. The counter knows no image: the render's claims (scheduler/tile_claims.h)
  // cut a range at its last tile and take one past it for "none left".
  TileRange claim();

 private:
  std::mutex& mpi_mutex_;
  const uint64_t tiles_per_claim_;
  MPI_Win window_ = MPI_WIN_NULL;
};

}  // namespace snee
