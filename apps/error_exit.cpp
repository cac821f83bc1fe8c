#include "apps/error_exit.h"

#include <cstdio>
#include <exception>

#include "scene/scene_loader.h"

namespace snee {

int run_reporting_errors(const std::function<int()>& command) {
  try {
    return command();
  } catch (const SceneError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}

}  // namespace snee
