// The fixture of the JSON scene format's tests (test_scene_loader.cpp, test_scene_errors.cpp): a
// fresh directory holding the meshes and environment image full_scene() names, loading from
// it, and the check that a bad input's SceneError names the file, the JSON path and what was
// expected.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene_loader.h"

namespace snee::test {

// A closed cube with inward (wrong) winding, and a lone open square, as OBJ text.
inline constexpr const char* kInsideOutCubeObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
    "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
inline constexpr const char* kOpenSquareObj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

inline const nlohmann::json kRemove = "<remove the key>";

struct BadCase {
  std::string name;
  std::string pointer;      // JSON pointer of the value to replace, or to remove
  nlohmann::json value;     // kRemove: remove the key
  std::string path;         // expected JSON path in the message
  std::string expectation;  // expected text in the message
};

// A small scene using every feature of the format, its files in the fixture's directory.
nlohmann::json full_scene();

class SceneLoaderTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  void write_env_exr();
  std::string scene_path() const { return (dir_ / "scene.json").string(); }
  LoadedScene load_text(const std::string& text);
  LoadedScene load(const nlohmann::json& doc) { return load_text(doc.dump(2)); }
  // Loads `doc` expecting a SceneError whose message has the file, `path` and `expectation`.
  void expect_error(const nlohmann::json& doc, const std::string& path,
                    const std::string& expectation);
  // Each case edits full_scene() and expects its error.
  void expect_errors(const std::vector<BadCase>& cases);
  // Loads `text` expecting a SceneError whose message contains `expected`.
  void expect_text_error(const std::string& text, const std::string& expected);

  std::filesystem::path dir_;
};

}  // namespace snee::test
