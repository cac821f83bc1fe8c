#include "apps/mpi/mpi_wait.h"

#include <chrono>
#include <cstdio>
#include <thread>

namespace snee {

void wait_or_abort(std::vector<MPI_Request>& requests, double seconds, const char* what,
                   MPI_Comm comm) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  for (;;) {
    int done = 0;
    MPI_Testall(static_cast<int>(requests.size()), requests.data(), &done, MPI_STATUSES_IGNORE);
    if (done) return;
    if (std::chrono::steady_clock::now() > deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::fprintf(stderr,
               "error: rank %d: the other processes did not %s within %.1f s (one may be stopped "
               "or hung; see --join-timeout); ending them all\n",
               rank, what, seconds);
  std::fflush(stderr);
  MPI_Abort(comm, 1);
}

}  // namespace snee
