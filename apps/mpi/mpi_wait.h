// Waiting on non-blocking MPI operations with a deadline, so that a stopped or hung process
// never holds the others for ever.
#pragma once

#include <mpi.h>

#include <vector>

namespace snee {

// Completes `requests` (MPI_Testall, polled), or, once `seconds` have passed, reports on
// stderr that the other processes did not `what` in time and ends every process with
// MPI_Abort (exit code 1).
void wait_or_abort(std::vector<MPI_Request>& requests, double seconds, const char* what,
                   MPI_Comm comm);

}  // namespace snee
