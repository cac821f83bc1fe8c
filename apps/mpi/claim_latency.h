// `snee-mpi claim-latency`: how long one tile claim takes (TileCounter::claim, an
// MPI_Fetch_and_op round trip to rank 0 and a flush), timed on every rank but 0 while rank 0
// computes without calling MPI, as it does while it renders, so that a claim that needed rank
// 0 to make progress would show. docs/performance.md ("Several processes") simulates many
// ranks from these figures.
#pragma once

#include <mpi.h>

namespace snee {

// Collective over `comm` (at least two processes). Every rank but 0 makes `claims` claims
// one after another; rank 0 spins for `busy_seconds` meanwhile, then prints a JSON object with
// each rank's median, mean, 90th percentile and largest claim in microseconds. Returns the exit
// code.
int measure_claim_latency(MPI_Comm comm, int claims, double busy_seconds);

}  // namespace snee
