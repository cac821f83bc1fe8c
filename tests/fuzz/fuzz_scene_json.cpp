// libFuzzer harness: a JSON scene through snee::load_scene_file, the reader `snee render` uses.
// The scratch directory also holds a small valid mesh of each format and an environment image
// under the names the seeds use (mesh.obj, mesh.ply, sky.ppm), so the fuzzer reaches the
// loader's mesh and envmap paths without reading anything outside that directory.
//
// Two outcomes are allowed: a SceneError, or a scene whose canonical form loads again to the
// same canonical form (the promise of scene/scene_loader.h). Anything else is a finding: a
// crash or sanitizer report, another exception escaping (e.g. one of nlohmann's), or a
// canonical document the loader itself rejects or reads differently.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include "scene/scene_error.h"
#include "scene/scene_loader.h"
#include "tests/fuzz/input_file.h"

namespace {

void write_fixtures() {
  // A tetrahedron, closed and wound outward.
  snee::fuzz::write_file("mesh.obj",
                         "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                         "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  snee::fuzz::write_file("mesh.ply",
                         "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                         "property float y\nproperty float z\nelement face 4\n"
                         "property list uchar int vertex_indices\nend_header\n"
                         "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  snee::fuzz::write_file("sky.ppm", "P3\n2 1\n255\n255 128 0 0 64 255\n");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool fixtures_written = (write_fixtures(), true);
  (void)fixtures_written;
  const std::string path = snee::fuzz::write_file("scene.json", data, size);
  std::optional<snee::LoadedScene> loaded;
  try {
    loaded = snee::load_scene_file(path);
  } catch (const snee::SceneError&) {
    return 0;
  }
  // A SceneError here is not caught: it escapes and libFuzzer reports it with its message.
  const snee::LoadedScene again =
      snee::load_scene_json(loaded->canonical, path, snee::fuzz::scratch_dir().string());
  if (again.canonical != loaded->canonical) {
    std::fprintf(stderr, "canonical form changed on reload:\n%s\nbecame\n%s\n",
                 loaded->canonical.dump().c_str(), again.canonical.dump().c_str());
    std::abort();
  }
  return 0;
}
