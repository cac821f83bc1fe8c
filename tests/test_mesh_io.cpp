// Mesh readers (OBJ, ASCII and binary PLY of both byte orders) on handmade files: what they
// read, and bad input named by file, line or element. Topology checks are test_mesh_topology.cpp.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "scene/mesh_io.h"
#include "scene/scene_error.h"
#include "tests/support/scene_error_of.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

class MeshIoTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("test_mesh_io"); }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& contents) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << contents;
    return path;
  }

  fs::path dir_;
};

using test::scene_error_of;

TEST_F(MeshIoTest, ObjPolygonsBecomeTriangleFans) {
  const std::string path = write("quad.obj",
                                 "# a quad and a triangle\n"
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 2.5\n"
                                 "f 1 2 3 4\n"
                                 "f 1/1/1 2/2/2 5/3/3\n");
  const TriangleMesh m = load_mesh(path);
  ASSERT_EQ(m.positions.size(), 5u);
  EXPECT_EQ(m.positions[4], Vec3(0, 0, 2.5f));
  const std::vector<uint32_t> expected = {0, 1, 2, 0, 2, 3, 0, 1, 4};
  EXPECT_EQ(m.indices, expected);
}

TEST_F(MeshIoTest, ObjIndexOutOfRangeNamesFileAndFace) {
  const std::string path = write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 7\n");
  const std::string message = scene_error_of([&] { load_obj(path); });
  EXPECT_NE(message.find("bad.obj"), std::string::npos) << message;
  EXPECT_NE(message.find("face 2"), std::string::npos) << message;
  EXPECT_NE(message.find("vertex 7"), std::string::npos) << message;
}

TEST_F(MeshIoTest, ObjNonFiniteCoordinateNamesVertex) {
  const std::string path = write("nan.obj", "v 0 0 0\nv 1 1e60 0\nv 0 1 0\nf 1 2 3\n");
  const std::string message = scene_error_of([&] { load_obj(path); });
  EXPECT_NE(message.find("nan.obj"), std::string::npos) << message;
  EXPECT_NE(message.find("vertex 2"), std::string::npos) << message;
}

TEST_F(MeshIoTest, MissingAndUnsupportedFilesNameTheFile) {
  const std::string missing = (dir_ / "missing.obj").string();
  EXPECT_NE(scene_error_of([&] { load_mesh(missing); }).find(missing), std::string::npos);
  const std::string missing_ply = (dir_ / "missing.ply").string();
  EXPECT_NE(scene_error_of([&] { load_mesh(missing_ply); }).find(missing_ply), std::string::npos);
  const std::string stl = write("thing.stl", "solid x\n");
  const std::string message = scene_error_of([&] { load_mesh(stl); });
  EXPECT_NE(message.find("thing.stl"), std::string::npos);
  EXPECT_NE(message.find(".obj or .ply"), std::string::npos);
}

// Exercises what real scans carry: extra scalar and list properties on the vertex, extra
// properties after the index list, and an element the reader does not know.
TEST_F(MeshIoTest, AsciiPlyIgnoresOtherPropertiesAndElements) {
  const std::string path = write("tri.ply",
                                 "ply\r\n"
                                 "format ascii 1.0\n"
                                 "comment made by hand\n"
                                 "element vertex 4\n"
                                 "property float x\n"
                                 "property float confidence\n"
                                 "property double y\n"
                                 "property list uchar float weights\n"
                                 "property float z\n"
                                 "element face 2\n"
                                 "property list uchar int vertex_indices\n"
                                 "property uchar red\n"
                                 "element edge 1\n"
                                 "property int vertex1\n"
                                 "property list int int path\n"
                                 "end_header\n"
                                 "0 0.5 0 2 9 9 0\n"
                                 "1 0.5 0 0 0\n"
                                 "1 0.5 1 1 7 0\n"
                                 "0 0.5 1 0 -1.5e1\n"
                                 "3 0 1 2 255\n"
                                 "4 0 2 3 1 12\n"
                                 "0 3 1 2 3\n");
  const TriangleMesh m = load_ply(path);
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.positions[2], Vec3(1, 1, 0));
  EXPECT_EQ(m.positions[3], Vec3(0, 1, -15));
  const std::vector<uint32_t> expected = {0, 1, 2, 0, 2, 3, 0, 3, 1};
  EXPECT_EQ(m.indices, expected);
}

// Corners that name different normals for one position split it; normals come out unit.
TEST_F(MeshIoTest, ObjVertexNormalsSplitWhereCornersDisagree) {
  const std::string path = write("normals.obj",
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                 "vn 0 0 1\nvn 0 3 4\n"
                                 "f 1//1 2//1 3//1\nf 1/1/2 3/1/2 4/1/2\nvt 0 0\n");
  const TriangleMesh m = load_mesh(path);
  ASSERT_EQ(m.positions.size(), 6u);
  const std::vector<uint32_t> expected = {0, 1, 2, 4, 5, 3};
  EXPECT_EQ(m.indices, expected);
  EXPECT_EQ(m.positions[4], m.positions[0]);
  EXPECT_EQ(m.positions[5], m.positions[2]);
  ASSERT_EQ(m.normals.size(), 6u);
  EXPECT_EQ(m.normals[0], Vec3(0, 0, 1));
  for (const uint32_t i : {3u, 4u, 5u}) {
    EXPECT_NEAR(m.normals[i].y, 0.6f, 1e-6f) << i;
    EXPECT_NEAR(m.normals[i].z, 0.8f, 1e-6f) << i;
  }
  // A face without normals makes the whole mesh flat.
  const TriangleMesh partial = load_mesh(write("partial.obj",
                                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                                               "f 1//1 2//1 3//1\nf 1 3 4\n"));
  EXPECT_TRUE(partial.normals.empty());
  EXPECT_EQ(partial.positions.size(), 4u);
}

TEST_F(MeshIoTest, BadVertexNormalsNameFileAndVertex) {
  const std::string zero =
      write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n");
  std::string message = scene_error_of([&] { load_mesh(zero); });
  EXPECT_NE(message.find(zero), std::string::npos) << message;
  EXPECT_NE(message.find("normal of vertex 1 is zero"), std::string::npos) << message;
  const std::string nan =
      write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 nan 1\nf 1//1 2//1 3//1\n");
  message = scene_error_of([&] { load_mesh(nan); });
  EXPECT_NE(message.find("line 4: normal 1 has a coordinate 'nan'"), std::string::npos) << message;
  const std::string range =
      write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n");
  message = scene_error_of([&] { load_mesh(range); });
  EXPECT_NE(message.find("face 1 refers to normal 2 but the file has 1 normals"), std::string::npos)
      << message;
}

// OBJ's v grows up the image, snee's down from its top row; a position whose corners name
// different texture coordinates (a seam) becomes one vertex per pair.
TEST_F(MeshIoTest, ObjTextureCoordinatesFlipVAndSplitAtSeams) {
  const std::string path = write("uvs.obj",
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                 "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.25\n"
                                 "f 1/1 2/2 3/3\nf 1/5 3/3 4/4\n");
  const TriangleMesh m = load_obj(path);
  ASSERT_EQ(m.positions.size(), 5u);
  const std::vector<uint32_t> expected = {0, 1, 2, 4, 2, 3};
  EXPECT_EQ(m.indices, expected);
  EXPECT_EQ(m.positions[4], m.positions[0]);
  EXPECT_TRUE(m.normals.empty());
  ASSERT_EQ(m.uvs.size(), 5u);
  const float expected_uv[5][2] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}, {0.25f, 1}};
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(m.uvs[i].u, expected_uv[i][0]) << i;
    EXPECT_EQ(m.uvs[i].v, expected_uv[i][1]) << i;
  }
  // With normals too, vertices split on the pair.
  const TriangleMesh both = load_obj(write("both.obj",
                                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 1 0\n"
                                           "vt 0 0\nvt 1 1\n"
                                           "f 1/1/1 2/1/1 3/1/1\nf 1/2/1 3/1/1 2/1/2\n"));
  ASSERT_EQ(both.positions.size(), 5u);
  ASSERT_EQ(both.uvs.size(), 5u);
  ASSERT_EQ(both.normals.size(), 5u);
  EXPECT_EQ(both.uvs[3].u, 1.0f);
  EXPECT_EQ(both.uvs[3].v, 0.0f);
  EXPECT_EQ(both.normals[3], Vec3(0, 0, 1));
  EXPECT_EQ(both.normals[4], Vec3(0, 1, 0));
  // A face without texture coordinates leaves the whole mesh without them.
  const TriangleMesh partial = load_obj(write("partial.obj",
                                              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\n"
                                              "f 1/1 2/1 3/1\nf 1 3 4\n"));
  EXPECT_TRUE(partial.uvs.empty());
  EXPECT_EQ(partial.positions.size(), 4u);
}

TEST_F(MeshIoTest, BadObjTextureCoordinatesNameFileAndLine) {
  const struct {
    const char* line;
    const char* expected;
  } cases[] = {
      {"vt nan 0",
       "line 4: texture coordinate 1 has a coordinate 'nan' that is not a finite number"},
      {"vt 0 1e39",
       "line 4: texture coordinate 1 has a coordinate '1e39' that is not a finite "
       "number"},
      {"vt", "line 4: texture coordinate 1 has no coordinates (expected u [v [w]])"},
      {"vt 0 0", "face 1 refers to texture coordinate 2 but the file has 1 texture coordinates"},
  };
  for (const auto& c : cases) {
    const std::string path =
        write("vt.obj", std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\n") + c.line + "\nf 1/1 2/1 3/2\n");
    const std::string message = scene_error_of([&] { load_obj(path); });
    EXPECT_NE(message.find("vt.obj: " + std::string(c.expected)), std::string::npos) << message;
  }
}

TEST_F(MeshIoTest, PlyVertexNormalsAreRead) {
  const std::string path = write("normals.ply",
                                 "ply\nformat ascii 1.0\nelement vertex 3\n"
                                 "property float x\nproperty float y\nproperty float z\n"
                                 "property float nx\nproperty float ny\nproperty float nz\n"
                                 "element face 1\nproperty list uchar int vertex_indices\n"
                                 "end_header\n"
                                 "0 0 0 0 0 2\n1 0 0 0 3 4\n0 1 0 1 0 0\n3 0 1 2\n");
  const TriangleMesh m = load_ply(path);
  ASSERT_EQ(m.normals.size(), 3u);
  EXPECT_EQ(m.normals[0], Vec3(0, 0, 1));
  EXPECT_NEAR(m.normals[1].y, 0.6f, 1e-6f);
  EXPECT_EQ(m.normals[2], Vec3(1, 0, 0));
  // Only nx and ny: no normals.
  const TriangleMesh partial = load_ply(write("partial.ply",
                                              "ply\nformat ascii 1.0\nelement vertex 3\n"
                                              "property float x\nproperty float y\n"
                                              "property float z\nproperty float nx\n"
                                              "property float ny\nelement face 1\n"
                                              "property list uchar int vertex_indices\n"
                                              "end_header\n"
                                              "0 0 0 0 0\n1 0 0 0 3\n0 1 0 1 0\n3 0 1 2\n"));
  EXPECT_TRUE(partial.normals.empty());
}

TEST_F(MeshIoTest, PlyTextureCoordinatesAreReadUnderTheirCommonNames) {
  for (const auto& [u, v] :
       {std::pair{"u", "v"}, std::pair{"s", "t"}, std::pair{"texture_u", "texture_v"}}) {
    const std::string path =
        write("uvs.ply", std::string("ply\nformat ascii 1.0\nelement vertex 3\n"
                                     "property float x\nproperty float y\nproperty float z\n"
                                     "property float ") +
                             u + "\nproperty float " + v +
                             "\nelement face 1\nproperty list uchar int vertex_indices\n"
                             "end_header\n"
                             "0 0 0 0 0\n1 0 0 1 0.25\n0 1 0 0.5 1\n3 0 1 2\n");
    const TriangleMesh m = load_ply(path);
    ASSERT_EQ(m.uvs.size(), 3u) << u;
    EXPECT_EQ(m.uvs[0].u, 0.0f) << u;
    EXPECT_EQ(m.uvs[0].v, 1.0f) << u;
    EXPECT_EQ(m.uvs[1].u, 1.0f) << u;
    EXPECT_EQ(m.uvs[1].v, 0.75f) << u;
    EXPECT_EQ(m.uvs[2].u, 0.5f) << u;
    EXPECT_EQ(m.uvs[2].v, 0.0f) << u;
    EXPECT_EQ(m.positions[2], Vec3(0, 1, 0)) << u;
  }
  // u alone: no texture coordinates.
  const TriangleMesh partial =
      load_ply(write("partial.ply",
                     "ply\nformat ascii 1.0\nelement vertex 3\n"
                     "property float x\nproperty float y\nproperty float z\nproperty float u\n"
                     "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                     "0 0 0 0\n1 0 0 1\n0 1 0 0.5\n3 0 1 2\n"));
  EXPECT_TRUE(partial.uvs.empty());
  EXPECT_EQ(partial.positions[1], Vec3(1, 0, 0));
}

TEST_F(MeshIoTest, AsciiPlyErrorsNameFileLineAndElement) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string bad_index = write("index.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  std::string message = scene_error_of([&] { load_ply(bad_index); });
  EXPECT_NE(message.find("index.ply"), std::string::npos) << message;
  EXPECT_NE(message.find("line 13"), std::string::npos) << message;
  EXPECT_NE(message.find("face 0"), std::string::npos) << message;
  EXPECT_NE(message.find("vertex index 3 is out of range"), std::string::npos) << message;

  const std::string bad_number = write("number.ply", header + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n");
  message = scene_error_of([&] { load_ply(bad_number); });
  EXPECT_NE(message.find("line 11"), std::string::npos) << message;
  EXPECT_NE(message.find("vertex 1"), std::string::npos) << message;
  EXPECT_NE(message.find("'y'"), std::string::npos) << message;

  const std::string infinite = write("inf.ply", header + "0 0 0\n1 0 inf\n0 1 0\n3 0 1 2\n");
  message = scene_error_of([&] { load_ply(infinite); });
  EXPECT_NE(message.find("line 11"), std::string::npos) << message;
  EXPECT_NE(message.find("finite number for property 'z'"), std::string::npos) << message;

  // Too short for the values the header declares: found before reading the body.
  const std::string truncated = write("short.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n");
  message = scene_error_of([&] { load_ply(truncated); });
  EXPECT_NE(message.find("line 7: 1 instances of element 'face'"), std::string::npos) << message;
  // Long enough, but the last index is missing.
  const std::string no_index = write("noindex.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1   \n");
  message = scene_error_of([&] { load_ply(no_index); });
  EXPECT_NE(message.find("face 0): expected a vertex index"), std::string::npos) << message;

  const std::string no_end = write("noend.ply", "ply\nformat ascii 1.0\nelement vertex 0\n");
  EXPECT_NE(scene_error_of([&] { load_ply(no_end); }).find("end_header"), std::string::npos);

  const std::string not_ply = write("text.ply", "hello\n");
  message = scene_error_of([&] { load_ply(not_ply); });
  EXPECT_NE(message.find("line 1"), std::string::npos) << message;

  const std::string no_faces =
      write("noface.ply",
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n0 0 0\n");
  EXPECT_NE(scene_error_of([&] { load_ply(no_faces); }).find("no 'face' element"),
            std::string::npos);
}

// Appends `value` in the given byte order.
template <typename T>
void put(std::string& out, T value, bool big_endian) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) {
    std::reverse(bytes, bytes + sizeof(T));
  }
  out.append(bytes, sizeof(T));
}

std::string binary_ply(bool big_endian, bool truncate) {
  std::string out = std::string("ply\nformat ") +
                    (big_endian ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\n"
                    "element vertex 4\n"
                    "property double x\nproperty float y\nproperty short tag\n"
                    "property float z\n"
                    "element material 1\nproperty list uchar uchar name\n"
                    "element face 2\n"
                    "property list int uint vertex_index\n"
                    "end_header\n";
  const double xs[4] = {0, 1, 1, 0.25};
  const float ys[4] = {0, 0, 1, 1};
  const float zs[4] = {-1, -1, -1, 3.5f};
  for (int i = 0; i < 4; ++i) {
    put<double>(out, xs[i], big_endian);
    put<float>(out, ys[i], big_endian);
    put<int16_t>(out, static_cast<int16_t>(-i), big_endian);
    put<float>(out, zs[i], big_endian);
  }
  put<uint8_t>(out, 3, big_endian);
  out += "abc";
  put<int32_t>(out, 3, big_endian);
  for (uint32_t i : {0u, 1u, 2u}) put<uint32_t>(out, i, big_endian);
  put<int32_t>(out, 4, big_endian);
  for (uint32_t i : {3u, 2u, 1u, 0u}) put<uint32_t>(out, i, big_endian);
  if (truncate) out.resize(out.size() - 2);
  return out;
}

class BinaryPlyTest : public MeshIoTest, public ::testing::WithParamInterface<bool> {};

TEST_P(BinaryPlyTest, ReadsEitherByteOrder) {
  const bool big_endian = GetParam();
  const TriangleMesh m = load_ply(write("mesh.ply", binary_ply(big_endian, false)));
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.positions[1], Vec3(1, 0, -1));
  EXPECT_EQ(m.positions[3], Vec3(0.25f, 1, 3.5f));
  const std::vector<uint32_t> expected = {0, 1, 2, 3, 2, 1, 3, 1, 0};
  EXPECT_EQ(m.indices, expected);
}

TEST_P(BinaryPlyTest, TruncatedFileNamesElementAndOffset) {
  const std::string path = write("cut.ply", binary_ply(GetParam(), true));
  const std::string message = scene_error_of([&] { load_ply(path); });
  EXPECT_NE(message.find("cut.ply"), std::string::npos) << message;
  EXPECT_NE(message.find("face 1"), std::string::npos) << message;
  EXPECT_NE(message.find("byte "), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(ByteOrder, BinaryPlyTest, ::testing::Values(false, true),
                         [](const auto& param_info) {
                           return param_info.param ? "BigEndian" : "LittleEndian";
                         });

// The header of a mesh with three float coordinates per vertex and one index list per face.
std::string ply_header(const std::string& format, const std::string& vertices,
                       const std::string& faces) {
  return "ply\nformat " + format + " 1.0\nelement vertex " + vertices +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + faces +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

// The body then started wherever the byte after the file's end was, and was read from there.
TEST_F(MeshIoTest, PlyEndHeaderWithoutNewlineIsAnError) {
  for (const char* format : {"binary_little_endian", "ascii"}) {
    std::string header = ply_header(format, "3", "1");
    header.pop_back();
    const std::string message = scene_error_of([&] { load_ply(write("cut.ply", header)); });
    EXPECT_NE(message.find("cut.ply: line 9: end_header must end with a newline"),
              std::string::npos)
        << message;
  }
}

// A header of a few bytes used to size arrays of gigabytes (std::bad_alloc, or RSS growing
// until the machine swapped) before the body was found to be missing.
TEST_F(MeshIoTest, PlyCountsTheBodyCannotHoldAreRejectedBeforeAllocating) {
  std::string message = scene_error_of([&] {
    load_ply(write("vertices.ply", ply_header("binary_little_endian", "1000000000", "1")));
  });
  EXPECT_NE(message.find("vertices.ply: line 3: 1000000000 instances of element 'vertex'"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("need at least 11.2 GiB of body, but the file has 0 bytes"),
            std::string::npos)
      << message;

  // Text: each value takes at least a digit and a separator.
  std::string body = "0 0 0\n1 0 0\n0 1 0\n";
  message = scene_error_of(
      [&] { load_ply(write("faces.ply", ply_header("ascii", "3", "100000000") + body)); });
  EXPECT_NE(message.find("faces.ply: line 7: 100000000 instances of element 'face'"),
            std::string::npos)
      << message;

  // Indices are 32-bit: a count beyond is refused before anything else is asked of it.
  message = scene_error_of(
      [&] { load_ply(write("many.ply", ply_header("binary_big_endian", "4294967297", "1"))); });
  EXPECT_NE(message.find("line 3: 4294967297 vertices, more than the 4294967296"),
            std::string::npos)
      << message;
}

// The reader looped over the instances of an element without properties, consuming nothing:
// 10^12 turns of nothing.
TEST_F(MeshIoTest, PlyElementWithoutPropertiesIsAnError) {
  const std::string header = ply_header("ascii", "3", "1");
  const std::string path =
      write("empty.ply", header.substr(0, header.find("end_header")) +
                             "element nothing 1000000000000\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                             "3 0 1 2\n");
  const std::string message = scene_error_of([&] { load_ply(path); });
  EXPECT_NE(message.find("line 9: element 'nothing' has instances but no properties"),
            std::string::npos)
      << message;
}

// A list length of 4e9 sized the corner array at 16 GB before reading a single corner.
TEST_F(MeshIoTest, PlyListLongerThanTheFileIsAnError) {
  std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
      "property uchar x\nproperty uchar y\nproperty uchar z\nelement face 1\n"
      "property list uint int vertex_indices\nend_header\n";
  binary += std::string(9, '\0');
  put<uint32_t>(binary, 4000000000u, false);
  for (int32_t i : {0, 1, 2}) put<int32_t>(binary, i, false);
  std::string message = scene_error_of([&] { load_ply(write("list.ply", binary)); });
  EXPECT_NE(message.find("list.ply: byte "), std::string::npos) << message;
  EXPECT_NE(message.find("(face 0): a list of 4000000000 items for property 'vertex_indices' is "
                         "longer than the rest of the file"),
            std::string::npos)
      << message;

  const std::string text =
      ply_header("ascii", "3", "1") + "0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n";
  message = scene_error_of([&] { load_ply(write("list_text.ply", text)); });
  EXPECT_NE(message.find("line 13 (face 0): a list of 4000000000 items"), std::string::npos)
      << message;
}

TEST_F(MeshIoTest, PlyAsciiNotANumberIsAnError) {
  const std::string path =
      write("nan.ply", ply_header("ascii", "3", "1") + "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n");
  const std::string message = scene_error_of([&] { load_ply(path); });
  EXPECT_NE(message.find("line 11 (vertex 1): expected a finite number for property 'x'"),
            std::string::npos)
      << message;
}

// Each vertex takes 3 bytes in the file and 12 in memory, so the file fits a budget its arrays
// exceed.
TEST_F(MeshIoTest, MeshBeyondTheMemoryBudgetIsAnError) {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1000\n"
      "property char x\nproperty char y\nproperty char z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  ply += std::string(3000, '\1');
  put<uint8_t>(ply, 3, false);
  for (int32_t i : {0, 1, 2}) put<int32_t>(ply, i, false);
  const std::string path = write("budget.ply", ply);
  EXPECT_EQ(load_ply(path).positions.size(), 1000u);

  std::string message = scene_error_of([&] { load_ply(path, MemoryBudget{8 << 10}); });
  EXPECT_NE(message.find("budget.ply: the arrays of 1000 vertices and 1 faces need 11.7 KiB, "
                         "more than the memory budget of 8.0 KiB (--max-memory)"),
            std::string::npos)
      << message;
  message = scene_error_of([&] { load_mesh(path, MemoryBudget{1000}); });
  EXPECT_NE(message.find("budget.ply: cannot read mesh: the file's bytes need 3.1 KiB, more than "
                         "the memory budget of 1000 bytes"),
            std::string::npos)
      << message;

  std::string obj;
  for (int i = 0; i < 300; ++i) obj += "v 0 0 0\n";
  obj += "f 1 2 3\n";
  message = scene_error_of([&] { load_obj(write("budget.obj", obj), MemoryBudget{8 << 10}); });
  EXPECT_NE(message.find("budget.obj: the arrays of 300 vertices and 3 face corners need"),
            std::string::npos)
      << message;
}

// A FIFO blocked the reader until someone wrote to it (for ever), and a device such as
// /dev/zero was read until memory ran out.
TEST_F(MeshIoTest, OnlyRegularFilesAreRead) {
  for (const char* name : {"fifo.ply", "fifo.obj"}) {
    const std::string fifo = (dir_ / name).string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
    const std::string message = scene_error_of([&] { load_mesh(fifo); });
    EXPECT_NE(message.find(fifo + ": cannot read mesh: it is a FIFO, not a regular file"),
              std::string::npos)
        << message;
  }
  const fs::path zero = dir_ / "zero.ply";
  fs::create_symlink("/dev/zero", zero);
  std::string message = scene_error_of([&] { load_mesh(zero.string()); });
  EXPECT_NE(message.find("it is a character device, not a regular file"), std::string::npos)
      << message;
  fs::create_directory(dir_ / "folder.obj");
  message = scene_error_of([&] { load_mesh((dir_ / "folder.obj").string()); });
  EXPECT_NE(message.find("it is a directory, not a regular file"), std::string::npos) << message;
}

// tinyobjloader opened every mtllib file, so one naming a FIFO hung the load; snee uses no
// materials from OBJ files, so none is opened.
TEST_F(MeshIoTest, ObjMaterialLibrariesAreNeverOpened) {
  const std::string fifo = (dir_ / "materials.mtl").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  fs::create_symlink("/dev/zero", dir_ / "zero.mtl");
  const TriangleMesh m = load_obj(
      write("lib.obj",
            "mtllib materials.mtl zero.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl wax\nf 1 2 3\n"));
  EXPECT_EQ(m.triangle_count(), 1u);
}

// tinyobjloader reads a coordinate it cannot parse as 0, so these loaded as other meshes.
TEST_F(MeshIoTest, ObjCoordinatesThatAreNotFiniteNumbersNameTheLine) {
  const struct {
    const char* vertex;
    const char* expected;
  } cases[] = {
      {"v nan 0 0", "vertex 2 has a coordinate 'nan' that is not a finite number"},
      {"v 0 -inf 0", "vertex 2 has a coordinate '-inf' that is not a finite number"},
      {"v 0 0 1e39", "vertex 2 has a coordinate '1e39' that is not a finite number"},
      {"v 0 zero 0", "vertex 2 has a coordinate 'zero' that is not a finite number"},
      {"v 1 2", "vertex 2 has 2 coordinates (expected x y z)"},
  };
  for (const auto& c : cases) {
    const std::string path = write("v.obj", std::string("# a triangle\r\nv 0 0 0\r\n") + c.vertex +
                                                "\r\nv 0 1 0\r\nf 1 2 3\r\n");
    const std::string message = scene_error_of([&] { load_obj(path); });
    EXPECT_NE(message.find("v.obj: line 3: " + std::string(c.expected)), std::string::npos)
        << message;
  }
  // What OBJ writers emit besides plain decimals still loads.
  const TriangleMesh m =
      load_obj(write("ok.obj", "v +1.5 -.5 2e-1\nv 1. 0 0 1\n\tv 0 1 0\nf 1 2 3\n"));
  EXPECT_EQ(m.positions[0], Vec3(1.5f, -0.5f, 0.2f));
}

// atoi wrapped 4294967298 round to 2, so the face silently used vertex 2 instead.
TEST_F(MeshIoTest, ObjCornerBeyondIntRangeIsAnError) {
  const std::string path = write("wrap.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 3 4294967298/1/1\n");
  const std::string message = scene_error_of([&] { load_obj(path); });
  EXPECT_NE(message.find("wrap.obj: line 4: face corner '4294967298/1/1' does not start with a "
                         "vertex number"),
            std::string::npos)
      << message;
  // Relative (negative) corners count back from the latest vertex.
  const TriangleMesh m = load_obj(write("relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"));
  const std::vector<uint32_t> expected = {0, 1, 2};
  EXPECT_EQ(m.indices, expected);
}

}  // namespace
}  // namespace snee
