// Reading the files a scene names (the scene file, meshes, environment images). Only regular
// files are read: a FIFO blocks its reader until someone writes to it, and a device such as
// /dev/zero never ends, so either would hang the load or fill memory. The file type is checked
// before opening (opening some devices has side effects) and again on the open descriptor, which
// is opened non-blocking so that a FIFO swapped in between cannot block the open itself.
#pragma once

#include <string>
#include <string_view>

#include "scene/memory_budget.h"

namespace snee {

// The whole content of `path`. Throws SceneError "<path>: cannot read <what>: <reason>" when it
// does not exist, is not a regular file (the message names its type), cannot be read, or holds
// more bytes than `budget` allows.
std::string read_input_file(const std::string& path, std::string_view what,
                            const MemoryBudget& budget);

// The same checks without reading, for files that a library opens by name itself. Leaves the
// window between this check and the library's open; read_input_file has none.
void require_regular_file(const std::string& path, std::string_view what);

}  // namespace snee
