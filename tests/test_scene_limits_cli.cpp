// The scene limits as a user meets them through the snee binary: the image-edge limit is the
// same for a scene file and --resolution, and a scene beyond the coordinate bound is a scene
// error (exit 2), never a render that Embree aborts.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/support/command_line.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class SceneLimitsCliTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("scene_limits"); }
  void TearDown() override { fs::remove_all(dir_); }

  // Writes a one-sphere scene with `camera` merged into its camera and returns its path.
  std::string write_scene(const json& camera) const {
    json scene = json::parse(R"({
      "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
      "shapes": [{"type": "sphere", "material": {"type": "diffuse"}}],
      "lights": [{"type": "constant"}]
    })");
    scene["camera"].update(camera);
    const std::string path = (dir_ / "scene.json").string();
    std::ofstream(path) << scene.dump();
    return path;
  }

  // Runs `snee render SCENE --spp 1 --quiet ARGS`, leaving its output in output_.
  int render(const std::string& scene, const std::string& args) {
    const fs::path log = dir_ / "output.txt";
    const int code =
        test::run_command("'" SNEE_BINARY "' render '" + scene + "' --spp 1 --quiet -o '" +
                              (dir_ / "out.exr").string() + "' " + args,
                          log);
    output_ = test::read_text_file(log);
    return code;
  }

  bool output_has(const std::string& text) const { return output_.find(text) != std::string::npos; }

  fs::path dir_;
  std::string output_;
};

// Scenes allowed 65536 pixels an edge, the command line 32768.
TEST_F(SceneLimitsCliTest, SceneAndCommandLineShareTheEdgeLimit) {
  EXPECT_EQ(render(write_scene({{"resolution", {32768, 1}}}), "--resolution 32768x1"), 0)
      << output_;
  EXPECT_EQ(render(write_scene({{"resolution", {32769, 1}}}), ""), 2) << output_;
  EXPECT_TRUE(output_has("camera.resolution[0]: expected an integer in [1, 32768], got 32769"))
      << output_;
  EXPECT_NE(render(write_scene(json::object()), "--resolution 1x32769"), 0) << output_;
  EXPECT_TRUE(output_has("expected WxH with sizes in [1, 32768], got '1x32769'")) << output_;
}

// A camera at 1e19 used to end the render in SIGABRT (exit 134) from Embree's ray check.
TEST_F(SceneLimitsCliTest, FarCameraIsASceneError) {
  const std::string scene = write_scene({{"position", {0, 0, 1e19}}});
  EXPECT_EQ(render(scene, ""), 2) << output_;
  EXPECT_TRUE(output_has(scene + ": camera.position: the camera position (0, 0, 1e+19) is beyond "
                                 "the coordinate bound"))
      << output_;
}

}  // namespace
}  // namespace snee
