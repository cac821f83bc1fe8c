// The glTF asset the glTF tests write (test_gltf.cpp, test_gltf_errors.cpp): a cube in a
// transformed node hierarchy with a camera, two lights and a transmitting material, as a
// .gltf with an embedded or external buffer or as a .glb, and the fixture that writes them.
#pragma once

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/test_directory.h"

namespace snee::test {

std::string base64(const std::string& bytes);

// A unit cube centred at the origin with 4 vertices per face (split where normals differ, as
// exporters write it), counter-clockwise seen from outside. Buffer: positions, normals, uvs,
// uint16 indices.
struct CubeBuffer {
  std::string bytes;
  size_t normals_offset = 0, uvs_offset = 0, indices_offset = 0;
};

CubeBuffer cube_buffer();

// The asset: a parent node translated by (0, 0, -3) holding a child scaled by 2 with the cube,
// a camera at the origin, a directional light shining down -y and a point light at (0, 4, 0).
// The cube's material is a rough transmitting volume named "jade". An empty `buffer_uri` leaves
// the buffer to a .glb's binary chunk.
nlohmann::json cube_document(const CubeBuffer& cube, const std::string& buffer_uri);

// The document and its binary chunk as a .glb file's bytes.
std::string glb(const nlohmann::json& doc, const std::string& bin);

class GltfTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_test_directory("test_gltf");
    cube_ = cube_buffer();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  nlohmann::json embedded() const {
    return cube_document(cube_, "data:application/octet-stream;base64," + base64(cube_.bytes));
  }

  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  std::string write_gltf(const nlohmann::json& doc, const std::string& name = "cube.gltf") const {
    return write(name, doc.dump(2));
  }

  std::filesystem::path dir_;
  CubeBuffer cube_;
};

}  // namespace snee::test
