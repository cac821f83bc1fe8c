// Reading an image (any format OpenImageIO reads: EXR, HDR, PNG, JPEG, TIFF, ...) into linear
// RGB, for environment maps and textures. Images with integer pixels (8- or 16-bit) are taken
// as sRGB-encoded and decoded, unless the file declares a linear colour space or holds data
// (PixelValues::kData); float images are linear already. One or two channels become grey; of more
// than three, the first three are used. Failures throw SceneError naming the file (or what stands
// for it) and `what` the image is for. Only a regular file is read (input_file.h), and the file and
// its decoded pixels must each fit in `budget`.
#pragma once

#include <string>
#include <string_view>

#include "scene/memory_budget.h"
#include "scene/scene.h"

namespace snee {

// What an image's pixels are: colours (an 8- or 16-bit file is sRGB-encoded unless it says
// otherwise), or data such as roughness, whose integer values v stand for v / max whatever
// colour space the file declares (as glTF has its metallic-roughness textures).
enum class PixelValues { kColour, kData };

// The image held in `bytes`; `path` names it in messages and its extension tells OpenImageIO
// the format where the content does not.
RgbImage decode_rgb_image(const std::string& bytes, const std::string& path, std::string_view what,
                          const MemoryBudget& budget, PixelValues values = PixelValues::kColour);

RgbImage read_rgb_image(const std::string& path, std::string_view what, const MemoryBudget& budget,
                        PixelValues values = PixelValues::kColour);

// read_rgb_image for a lat-long environment map (what = "environment image").
RgbImage read_env_image(const std::string& path, const MemoryBudget& budget = {});

}  // namespace snee
