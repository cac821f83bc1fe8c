// The command line's error contract, shared by snee and snee-mpi: what a subcommand throws
// becomes "error: ..." on stderr and an exit code (1 = failure, 2 = bad scene).
#pragma once

#include <functional>

namespace snee {

int run_reporting_errors(const std::function<int()>& command);

}  // namespace snee
