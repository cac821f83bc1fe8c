// The one exception type of the scene layer. Loaders of meshes, images and scene files throw it
// with a message that names the file and the place in it (line, element or JSON path) and says
// what was expected, so a user can fix the input without reading code.
#pragma once

#include <stdexcept>

namespace snee {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace snee
