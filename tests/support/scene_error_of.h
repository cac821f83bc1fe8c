// For tests of bad input: the message a loader's SceneError carries.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "scene/scene_error.h"

namespace snee::test {

// Message of the SceneError that `f` throws, or a failure if it throws none.
template <typename F>
std::string scene_error_of(F f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no SceneError thrown";
  return "";
}

}  // namespace snee::test
