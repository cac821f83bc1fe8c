// libFuzzer harness for the mesh readers, built twice (tests/fuzz/CMakeLists.txt): as fuzz_obj
// with SNEE_FUZZ_MESH_FILE "input.obj" (tinyobjloader plus snee's checks) and as fuzz_ply with
// "input.ply" (snee's own ASCII and binary reader); snee::load_mesh picks the reader by that
// extension. Bad input must end in a SceneError; any other exception, crash, leak or sanitizer
// report is a finding.
#include <cstddef>
#include <cstdint>

#include "scene/mesh_io.h"
#include "scene/scene_error.h"
#include "tests/fuzz/input_file.h"
#include "tests/fuzz/mesh_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    snee::TriangleMesh mesh =
        snee::load_mesh(snee::fuzz::write_file(SNEE_FUZZ_MESH_FILE, data, size));
    snee::fuzz::run_loader_mesh_checks(mesh);
  } catch (const snee::SceneError&) {
  }
  return 0;
}
