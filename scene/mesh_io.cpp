#include "scene/mesh_io.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

#include "scene/scene_error.h"

namespace snee {

namespace {

std::string lowercase_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

TriangleMesh load_mesh(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  if (ext == ".obj") return load_obj(path);
  if (ext == ".ply") return load_ply(path);
  throw SceneError(path + ": unsupported mesh format '" + ext + "' (expected .obj or .ply)");
}

TriangleMesh load_obj(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) {
    throw SceneError(path + ": cannot read mesh: no such file");
  }
  tinyobj::ObjReaderConfig config;
  // Triangulating ourselves keeps the file's face numbers available for error messages.
  config.triangulate = false;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    std::string error = reader.Error();
    while (!error.empty() && std::isspace(static_cast<unsigned char>(error.back()))) {
      error.pop_back();
    }
    throw SceneError(path + ": cannot read OBJ mesh: " + error);
  }

  const std::vector<float>& v = reader.GetAttrib().vertices;
  TriangleMesh mesh;
  mesh.positions.resize(v.size() / 3);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    mesh.positions[i] = Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    if (!is_finite(mesh.positions[i])) {
      throw SceneError(path + ": vertex " + std::to_string(i + 1) +
                       " has a coordinate that is not a finite number");
    }
  }

  size_t face_number = 0;  // across all groups, 1-based in messages like the file's own counting
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const std::vector<tinyobj::index_t>& corners = shape.mesh.indices;
    size_t first = 0;
    for (const unsigned int face_size : shape.mesh.num_face_vertices) {
      ++face_number;
      if (face_size < 3) {
        throw SceneError(path + ": face " + std::to_string(face_number) + " has " +
                         std::to_string(face_size) + " vertices (expected at least 3)");
      }
      for (size_t k = 0; k < face_size; ++k) {
        const int index = corners[first + k].vertex_index;
        if (index < 0 || static_cast<size_t>(index) >= mesh.positions.size()) {
          throw SceneError(path + ": face " + std::to_string(face_number) + " refers to vertex " +
                           std::to_string(index + 1) + " but the file has " +
                           std::to_string(mesh.positions.size()) + " vertices");
        }
      }
      for (size_t k = 1; k + 1 < face_size; ++k) {
        mesh.indices.push_back(static_cast<uint32_t>(corners[first].vertex_index));
        mesh.indices.push_back(static_cast<uint32_t>(corners[first + k].vertex_index));
        mesh.indices.push_back(static_cast<uint32_t>(corners[first + k + 1].vertex_index));
      }
      first += face_size;
    }
  }
  if (mesh.indices.empty()) throw SceneError(path + ": the OBJ file has no faces");
  return mesh;
}

}  // namespace snee
