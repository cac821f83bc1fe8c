#include "apps/mpi/stop_together.h"

namespace snee {
namespace {

constexpr int kStopTag = 7;
constexpr auto kPollInterval = std::chrono::milliseconds(5);

}  // namespace

StopTogether::StopTogether(MPI_Comm comm, std::mutex& mpi_mutex)
    : comm_(comm), mpi_mutex_(mpi_mutex) {
  MPI_Irecv(&incoming_status_, 1, MPI_INT, MPI_ANY_SOURCE, kStopTag, comm_, &incoming_request_);
}

StopTogether::~StopTogether() {
  if (incoming_request_ == MPI_REQUEST_NULL) return;
  MPI_Cancel(&incoming_request_);
  MPI_Wait(&incoming_request_, MPI_STATUS_IGNORE);
}

bool StopTogether::operator()(int exit_status) {
  if (stopping_.load(std::memory_order_relaxed)) return true;
  std::unique_lock<std::mutex> lock(mpi_mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return false;
  const auto now = std::chrono::steady_clock::now();
  if (exit_status == 0 && now < next_poll_) return false;
  next_poll_ = now + kPollInterval;
  if (exit_status != 0 && !told_others_) {
    told_others_ = true;
    outgoing_status_ = exit_status;
    int ranks = 1, rank = 0;
    MPI_Comm_size(comm_, &ranks);
    MPI_Comm_rank(comm_, &rank);
    for (int other = 0; other < ranks; ++other) {
      if (other == rank) continue;
      // One int goes out eagerly; nothing waits for a process that may never receive it.
      MPI_Request sent;
      MPI_Isend(&outgoing_status_, 1, MPI_INT, other, kStopTag, comm_, &sent);
      MPI_Request_free(&sent);
    }
  }
  int arrived = 0;
  if (incoming_request_ != MPI_REQUEST_NULL)
    MPI_Test(&incoming_request_, &arrived, MPI_STATUS_IGNORE);
  if (exit_status != 0 || arrived) stopping_.store(true, std::memory_order_relaxed);
  return stopping_.load(std::memory_order_relaxed);
}

}  // namespace snee
