#include "scheduler/schedule.h"

#include <stdexcept>

namespace snee {

const char* schedule_name(Schedule s) {
  switch (s) {
    case Schedule::kMegakernel:
      return "megakernel";
    case Schedule::kLocal:
      return "local";
    case Schedule::kGlobal:
      return "global";
  }
  return "?";
}

Schedule parse_schedule(const std::string& name) {
  if (name == "megakernel") return Schedule::kMegakernel;
  if (name == "local") return Schedule::kLocal;
  if (name == "global") return Schedule::kGlobal;
  throw std::invalid_argument("unknown schedule '" + name +
                              "' (expected megakernel, local or global)");
}

}  // namespace snee
