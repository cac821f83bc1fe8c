// Gathers the shards of a render split across MPI processes into rank 0's result. Each pixel
// belongs to one shard and is black in the others, so a sum gives the single-process image bit
// for bit (adding zeros changes no bit of a non-negative value).
#pragma once

#include <mpi.h>

#include "scheduler/render.h"

namespace snee {

// Collective over `comm`: every rank calls it after rendering its tiles (its shard, or those it
// claimed). On rank 0 `result` becomes the whole render's (film, paths, rays and tile seconds
// summed, the slowest rank's times, CPU time summed, and each rank's ProcessShare in
// stats.processes); on every rank `exit_status` becomes the largest of the ranks' (a signal's 128 +
// its number wins over 1, so a render stopped by SIGTERM anywhere exits 143 everywhere). A rank
// that waits longer than `timeout_seconds` for the others ends them all (mpi_wait.h). Returns
// whether this rank is rank 0.
bool join_shards(RenderResult& result, int& exit_status, double timeout_seconds, MPI_Comm comm);

}  // namespace snee
