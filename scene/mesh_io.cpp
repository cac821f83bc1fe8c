#include "scene/mesh_io.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "scene/input_file.h"
#include "scene/scene_error.h"
#include "scene/vertex_normals.h"

namespace snee {

namespace {

std::string lowercase_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

struct ObjCounts {
  size_t vertices = 0;
  size_t normals = 0;    // vn lines
  size_t texcoords = 0;  // vt lines
  size_t corners = 0;    // over all faces
};

bool is_obj_space(char c) {
  return c == ' ' || c == '\t';
}

std::vector<std::string_view> obj_words(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_obj_space(line[i])) ++i;
    size_t j = i;
    while (j < line.size() && !is_obj_space(line[j])) ++j;
    if (j > i) words.push_back(line.substr(i, j - i));
    i = j;
  }
  return words;
}

// from_chars reads no leading '+', which OBJ writers do emit.
std::string_view without_plus(std::string_view word) {
  if (word.size() > 1 && word[0] == '+' && word[1] != '+' && word[1] != '-') word.remove_prefix(1);
  return word;
}

// What one face corner names besides its position: the normal and texture coordinates numbers
// (0 where the mesh keeps none).
constexpr uint32_t kUnusedVertex = ~uint32_t{0};
struct CornerAttributes {
  uint32_t vertex = kUnusedVertex;
  int normal = 0;
  int texcoord = 0;
  bool operator==(const CornerAttributes&) const = default;
};

struct CornerAttributesHash {
  size_t operator()(const CornerAttributes& a) const {
    const uint64_t attributes =
        (uint64_t{static_cast<uint32_t>(a.normal)} << 32) | static_cast<uint32_t>(a.texcoord);
    return std::hash<uint64_t>()(attributes * 0x9E3779B97F4A7C15ull ^ a.vertex);
  }
};

// A whole word that reads as a number finite in float.
bool is_finite_number(std::string_view word) {
  word = without_plus(word);
  double value = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  return ec == std::errc() && end == word.data() + word.size() &&
         std::isfinite(static_cast<float>(value));
}

// tinyobjloader lets two kinds of damage through silently: a coordinate it cannot parse
// ("nan", "inf", a missing one) becomes 0, and a corner number past int range wraps round in
// atoi to some other vertex. This pass rejects both, splitting the text as tinyobjloader does
// (lines end at \n, \r or \r\n and stop at a NUL; words are separated by spaces and tabs), and
// counts what its arrays will hold.
ObjCounts check_obj_text(const std::string& path, std::string_view text) {
  ObjCounts counts;
  size_t line_number = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    const size_t eol = std::min(text.find_first_of("\r\n", pos), text.size());
    std::string_view line = text.substr(pos, eol - pos);
    pos = eol + (text.compare(eol, 2, "\r\n") == 0 ? 2 : 1);
    ++line_number;
    line = line.substr(0, line.find('\0'));
    const std::vector<std::string_view> words = obj_words(line);
    if (words.empty()) continue;
    auto fail = [&](const std::string& what) {
      return SceneError(path + ": line " + std::to_string(line_number) + ": " + what);
    };
    if (words[0] == "v" || words[0] == "vn") {
      const bool normal = words[0] == "vn";
      const std::string vertex = normal ? "normal " + std::to_string(++counts.normals)
                                        : "vertex " + std::to_string(++counts.vertices);
      if (words.size() < 4) {
        throw fail(vertex + " has " + std::to_string(words.size() - 1) +
                   " coordinates (expected x y z)");
      }
      for (size_t k = 1; k <= 3; ++k) {
        if (!is_finite_number(words[k])) {
          throw fail(vertex + " has a coordinate '" + std::string(words[k]) +
                     "' that is not a finite number");
        }
      }
    } else if (words[0] == "vt") {
      // "vt u [v [w]]": only u and v are used, v is 0 where missing as tinyobjloader reads it.
      const std::string texcoord = "texture coordinate " + std::to_string(++counts.texcoords);
      if (words.size() < 2) throw fail(texcoord + " has no coordinates (expected u [v [w]])");
      for (size_t k = 1; k < std::min<size_t>(words.size(), 3); ++k) {
        if (!is_finite_number(words[k])) {
          throw fail(texcoord + " has a coordinate '" + std::string(words[k]) +
                     "' that is not a finite number");
        }
      }
    } else if (words[0] == "f") {
      for (size_t k = 1; k < words.size(); ++k) {
        // Of "v", "v/vt", "v//vn" or "v/vt/vn", only the vertex number matters to us.
        const std::string_view word = without_plus(words[k].substr(0, words[k].find('/')));
        int index = 0;
        const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), index);
        if (ec != std::errc() || end != word.data() + word.size() || index == 0) {
          throw fail("face corner '" + std::string(words[k]) +
                     "' does not start with a vertex number (a non-zero integer within int "
                     "range)");
        }
      }
      counts.corners += words.size() - 1;
    }
  }
  return counts;
}

}  // namespace

TriangleMesh load_mesh(const std::string& path, const MemoryBudget& budget) {
  const std::string ext = lowercase_extension(path);
  if (ext == ".obj") return load_obj(path, budget);
  if (ext == ".ply") return load_ply(path, budget);
  throw SceneError(path + ": unsupported mesh format '" + ext + "' (expected .obj or .ply)");
}

TriangleMesh load_obj(const std::string& path, const MemoryBudget& budget) {
  std::string text = read_input_file(path, "mesh", budget);
  const ObjCounts counts = check_obj_text(path, text);
  // tinyobjloader's arrays grow by doubling, so each may hold up to twice what it needs, and
  // ours follow: a position per vertex, at most three indices per corner.
  const uint64_t array_bytes = saturating_add(
      saturating_add(
          saturating_multiply(counts.vertices, 2 * 3 * sizeof(tinyobj::real_t) + 2 * sizeof(Vec3)),
          saturating_add(saturating_multiply(counts.normals, 2 * 3 * sizeof(tinyobj::real_t)),
                         saturating_multiply(counts.texcoords, 2 * 2 * sizeof(tinyobj::real_t)))),
      // A corner may split its vertex (a position, a normal and texture coordinates more).
      saturating_multiply(counts.corners, 2 * (sizeof(tinyobj::index_t) + sizeof(unsigned int)) +
                                              3 * sizeof(uint32_t) + 2 * sizeof(Vec3) + sizeof(Uv) +
                                              sizeof(CornerAttributes)));
  if (!budget.allows(array_bytes)) {
    throw SceneError(path + ": " +
                     budget.exceeded("the arrays of " + std::to_string(counts.vertices) +
                                         " vertices and " + std::to_string(counts.corners) +
                                         " face corners",
                                     array_bytes));
  }

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  std::istringstream stream(std::move(text));
  // No material reader: tinyobjloader then skips mtllib lines instead of opening the files
  // they name, which could be anything (a device, a FIFO) and are never used. Triangulating
  // ourselves keeps the file's face numbers available for error messages.
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &stream,
                        /*readMatFn=*/nullptr, /*triangulate=*/false,
                        /*default_vcols_fallback=*/false)) {
    while (!error.empty() && std::isspace(static_cast<unsigned char>(error.back()))) {
      error.pop_back();
    }
    throw SceneError(path + ": cannot read OBJ mesh: " + error);
  }

  const std::vector<float>& v = attrib.vertices;
  TriangleMesh mesh;
  mesh.positions.resize(v.size() / 3);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    mesh.positions[i] = Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    if (!is_finite(mesh.positions[i])) {
      throw SceneError(path + ": vertex " + std::to_string(i + 1) +
                       " has a coordinate that is not a finite number");
    }
  }

  // Vertex normals, and texture coordinates, only where every face corner names one (v//vn,
  // v/vt, v/vt/vn); otherwise the mesh is flat-shaded, or has no texture coordinates.
  const size_t normal_count = attrib.normals.size() / 3;
  const size_t texcoord_count = attrib.texcoords.size() / 2;
  bool with_normals = normal_count > 0;
  bool with_uvs = texcoord_count > 0;
  for (const tinyobj::shape_t& shape : shapes) {
    for (const tinyobj::index_t& corner : shape.mesh.indices) {
      with_normals = with_normals && corner.normal_index >= 0;
      with_uvs = with_uvs && corner.texcoord_index >= 0;
    }
  }
  // A position whose corners name different normals or texture coordinates becomes one vertex
  // per pair: the first keeps the file's number, the others are appended.
  const bool with_attributes = with_normals || with_uvs;
  std::vector<CornerAttributes> attributes_of(with_attributes ? mesh.positions.size() : 0);
  std::unordered_map<CornerAttributes, uint32_t, CornerAttributesHash> split;
  const auto corner_vertex = [&](const tinyobj::index_t& corner) -> uint32_t {
    const auto vertex = static_cast<uint32_t>(corner.vertex_index);
    if (!with_attributes) return vertex;
    const CornerAttributes wanted{vertex, with_normals ? corner.normal_index : 0,
                                  with_uvs ? corner.texcoord_index : 0};
    CornerAttributes& first = attributes_of[vertex];
    if (first.vertex == kUnusedVertex) first = wanted;
    if (first == wanted) return vertex;
    const auto [it, added] =
        split.try_emplace(wanted, static_cast<uint32_t>(mesh.positions.size()));
    if (added) {
      mesh.positions.push_back(mesh.positions[vertex]);
      attributes_of.push_back(wanted);
    }
    return it->second;
  };

  size_t face_number = 0;  // across all groups, 1-based in messages like the file's own counting
  for (const tinyobj::shape_t& shape : shapes) {
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
        const int normal = corners[first + k].normal_index;
        if (with_normals && static_cast<size_t>(normal) >= normal_count) {
          throw SceneError(path + ": face " + std::to_string(face_number) + " refers to normal " +
                           std::to_string(normal + 1) + " but the file has " +
                           std::to_string(normal_count) + " normals");
        }
        const int texcoord = corners[first + k].texcoord_index;
        if (with_uvs && static_cast<size_t>(texcoord) >= texcoord_count) {
          throw SceneError(path + ": face " + std::to_string(face_number) +
                           " refers to texture coordinate " + std::to_string(texcoord + 1) +
                           " but the file has " + std::to_string(texcoord_count) +
                           " texture coordinates");
        }
      }
      for (size_t k = 1; k + 1 < face_size; ++k) {
        mesh.indices.push_back(corner_vertex(corners[first]));
        mesh.indices.push_back(corner_vertex(corners[first + k]));
        mesh.indices.push_back(corner_vertex(corners[first + k + 1]));
      }
      first += face_size;
    }
  }
  if (mesh.indices.empty()) throw SceneError(path + ": the OBJ file has no faces");
  // A vertex no face uses is never shaded nor textured; any values will do.
  const auto used = [&](size_t i) { return attributes_of[i].vertex != kUnusedVertex; };
  if (with_normals) {
    const std::vector<float>& vn = attrib.normals;
    mesh.normals.resize(mesh.positions.size());
    for (size_t i = 0; i < mesh.normals.size(); ++i) {
      const auto n = static_cast<size_t>(attributes_of[i].normal);
      mesh.normals[i] = used(i) ? Vec3(vn[3 * n], vn[3 * n + 1], vn[3 * n + 2]) : Vec3(0, 0, 1);
    }
    normalize_vertex_normals(mesh, path);
  }
  if (with_uvs) {
    const std::vector<float>& vt = attrib.texcoords;
    mesh.uvs.resize(mesh.positions.size());
    for (size_t i = 0; i < mesh.uvs.size(); ++i) {
      const auto t = static_cast<size_t>(attributes_of[i].texcoord);
      // OBJ's v grows up the image, snee's (like glTF's) down from its top row.
      if (used(i)) mesh.uvs[i] = {vt[2 * t], 1.0f - vt[2 * t + 1]};
    }
  }
  return mesh;
}

}  // namespace snee
