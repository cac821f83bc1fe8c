// Reading a lat-long environment image (any format OpenImageIO reads: EXR, HDR, PNG, ...) into
// linear RGB. Images with integer pixels (8- or 16-bit) are taken as sRGB-encoded and decoded,
// unless the file declares a linear colour space; float images are linear already. One or two
// channels become grey; of more than three, the first three are used. Failures throw SceneError
// naming the file. Only a regular file is read (input_file.h), and the file and its decoded
// pixels must each fit in `budget`.
#pragma once

#include <string>

#include "scene/memory_budget.h"
#include "scene/scene.h"

namespace snee {

EnvImage read_env_image(const std::string& path, const MemoryBudget& budget = {});

}  // namespace snee
