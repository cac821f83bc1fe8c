// libFuzzer harness: an environment image through snee::read_env_image. The file name has no
// known extension, so OpenImageIO tries each of its readers in turn and the fuzzer can reach
// any format (EXR, HDR, PFM, PNM, PNG, ...) from the seeds. OpenImageIO itself is not
// instrumented; what this mostly exercises is snee's use of the header (image size, channel
// count) and of the decoded pixels.
#include <cstddef>
#include <cstdint>

#include "scene/rgb_image_io.h"
#include "scene/scene_error.h"
#include "tests/fuzz/input_file.h"

// Well below libFuzzer's 2 GB RSS limit (scripts/fuzz.sh), so that a header the budget should
// have refused shows as a finding rather than passing because the machine is large.
constexpr uint64_t kBudgetBytes = uint64_t{512} << 20;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    snee::read_env_image(snee::fuzz::write_file("input.image", data, size),
                         snee::MemoryBudget{kBudgetBytes});
  } catch (const snee::SceneError&) {
  }
  return 0;
}
