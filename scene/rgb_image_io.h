// Reading an image (any format OpenImageIO reads: EXR, HDR, PNG, JPEG, TIFF, ...) into linear
// RGB, for environment maps and textures. Images with integer pixels (8- or 16-bit) are taken
// as sRGB-encoded and decoded, unless the file declares a linear colour space; float images are
// linear already. One or two channels become grey; of more than three, the first three are used.
// Failures throw SceneError naming the file (or what stands for it) and `what` the image is for.
// Only a regular file is read (input_file.h), and the file and its decoded pixels must each fit
// in `budget`.
#pragma once

#include <string>
#include <string_view>

#include "scene/memory_budget.h"
#include "scene/scene.h"

namespace snee {

// The image held in `bytes`; `path` names it in messages and its extension tells OpenImageIO
// the format where the content does not.
RgbImage decode_rgb_image(const std::string& bytes, const std::string& path, std::string_view what,
                          const MemoryBudget& budget);

RgbImage read_rgb_image(const std::string& path, std::string_view what, const MemoryBudget& budget);

// read_rgb_image for a lat-long environment map (what = "environment image").
RgbImage read_env_image(const std::string& path, const MemoryBudget& budget = {});

}  // namespace snee
