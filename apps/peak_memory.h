// Peak resident memory of this process, so one process can measure several runs one after
// another: Linux lets a process reset its peak ("5" into /proc/self/clear_refs) and reports it
// as VmHWM in /proc/self/status. Where that is unavailable the figure is the lifetime peak
// that getrusage reports, and reset_peak_memory() says so by returning false.
#pragma once

namespace snee {

// Returns freed heap pages to the system first, so an earlier, larger run does not count.
bool reset_peak_memory();
double peak_memory_since_reset_mib();

}  // namespace snee
