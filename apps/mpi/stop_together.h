// Makes the processes of a split render stop together: a signal to any one of them (SIGTERM
// from a batch system, Ctrl-C) is sent on to the others, so no process renders on alone while
// the rest wait for it in the join.
#pragma once

#include <mpi.h>

#include <atomic>
#include <chrono>
#include <mutex>

namespace snee {

class StopTogether {
 public:
  // `mpi_mutex` serializes this process's MPI calls; the tile counter's claims share it.
  StopTogether(MPI_Comm comm, std::mutex& mpi_mutex);
  ~StopTogether();  // withdraws the pending receive
  StopTogether(const StopTogether&) = delete;
  StopTogether& operator=(const StopTogether&) = delete;

  // RenderDistribution::stop_together: `exit_status` is this process's (0: no signal). Asked
  // from every render thread, often: it talks to MPI at most every few milliseconds, from one
  // thread at a time (MPI_THREAD_SERIALIZED is enough); it skips a poll rather than wait
  // while another thread talks to MPI.
  bool operator()(int exit_status);

 private:
  const MPI_Comm comm_;
  std::mutex& mpi_mutex_;
  std::chrono::steady_clock::time_point next_poll_{};
  MPI_Request incoming_request_ = MPI_REQUEST_NULL;
  int incoming_status_ = 0;
  int outgoing_status_ = 0;  // the buffer of the sends, which outlive the call
  bool told_others_ = false;
  std::atomic<bool> stopping_{false};
};

}  // namespace snee
