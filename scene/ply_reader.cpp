// PLY (Turk 1994): a text header declares elements, each with a count and a property list, then
// the body stores the elements in order, as text or as packed binary of either byte order.
// The dragon scan is a 34 MB text file, so numbers are parsed with std::from_chars over the
// whole file in memory rather than through streams.
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/input_file.h"
#include "scene/mesh_io.h"
#include "scene/scene_error.h"
#include "scene/vertex_normals.h"

namespace snee {

namespace {

enum class PlyType : uint8_t {
  kInt8,
  kUint8,
  kInt16,
  kUint16,
  kInt32,
  kUint32,
  kFloat32,
  kFloat64
};

std::optional<PlyType> parse_type(std::string_view name) {
  if (name == "char" || name == "int8") return PlyType::kInt8;
  if (name == "uchar" || name == "uint8") return PlyType::kUint8;
  if (name == "short" || name == "int16") return PlyType::kInt16;
  if (name == "ushort" || name == "uint16") return PlyType::kUint16;
  if (name == "int" || name == "int32") return PlyType::kInt32;
  if (name == "uint" || name == "uint32") return PlyType::kUint32;
  if (name == "float" || name == "float32") return PlyType::kFloat32;
  if (name == "double" || name == "float64") return PlyType::kFloat64;
  return std::nullopt;
}

size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 0;
}

bool is_integer(PlyType t) {
  return t != PlyType::kFloat32 && t != PlyType::kFloat64;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  // of the items, for a list
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;
};

struct PlyElement {
  std::string name;
  size_t count = 0;
  std::vector<PlyProperty> properties;
  size_t header_line = 0;  // of its "element" line, for messages about the count
};

enum class PlyFormat : uint8_t { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  size_t body_offset = 0;  // first byte after "end_header\n"
  size_t body_line = 0;    // line number of the first body line
};

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
    if (j > i) words.push_back(line.substr(i, j - i));
    i = j;
  }
  return words;
}

PlyHeader parse_header(const std::string& path, std::string_view data) {
  PlyHeader header;
  size_t pos = 0;
  size_t line_number = 0;
  bool seen_format = false;
  auto fail = [&](const std::string& what) -> SceneError {
    return SceneError(path + ": line " + std::to_string(line_number) + ": " + what);
  };
  while (true) {
    if (pos >= data.size()) {
      throw SceneError(path + ": the PLY header has no end_header line");
    }
    const size_t eol = data.find('\n', pos);
    const bool last_line = eol == std::string_view::npos;
    const std::string_view line = data.substr(pos, last_line ? std::string_view::npos : eol - pos);
    pos = last_line ? data.size() : eol + 1;
    ++line_number;
    const std::vector<std::string_view> w = split_words(line);

    if (line_number == 1) {
      if (w.size() != 1 || w[0] != "ply") throw fail("not a PLY file (expected 'ply' first)");
      continue;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") {
      // The body starts after the newline, so without one there is no telling where it starts.
      if (last_line) throw fail("end_header must end with a newline before the body");
      break;
    }
    if (w[0] == "format") {
      if (w.size() != 3) throw fail("expected 'format <ascii|binary_*> 1.0'");
      if (w[1] == "ascii") {
        header.format = PlyFormat::kAscii;
      } else if (w[1] == "binary_little_endian") {
        header.format = PlyFormat::kBinaryLittleEndian;
      } else if (w[1] == "binary_big_endian") {
        header.format = PlyFormat::kBinaryBigEndian;
      } else {
        throw fail("unknown format '" + std::string(w[1]) + "'");
      }
      seen_format = true;
    } else if (w[0] == "element") {
      size_t count = 0;
      if (w.size() != 3 ||
          std::from_chars(w[2].data(), w[2].data() + w[2].size(), count).ec != std::errc()) {
        throw fail("expected 'element <name> <count>'");
      }
      header.elements.push_back({std::string(w[1]), count, {}, line_number});
    } else if (w[0] == "property") {
      if (header.elements.empty()) throw fail("property declared before any element");
      PlyProperty property;
      if (w.size() == 5 && w[1] == "list") {
        const auto count_type = parse_type(w[2]);
        const auto item_type = parse_type(w[3]);
        if (!count_type || !is_integer(*count_type) || !item_type) {
          throw fail("expected 'property list <integer type> <type> <name>'");
        }
        property = {std::string(w[4]), *item_type, true, *count_type};
      } else if (w.size() == 3) {
        const auto type = parse_type(w[1]);
        if (!type) throw fail("unknown property type '" + std::string(w[1]) + "'");
        property.name = std::string(w[2]);
        property.type = *type;
      } else {
        throw fail("expected 'property <type> <name>' or 'property list <type> <type> <name>'");
      }
      header.elements.back().properties.push_back(property);
    } else {
      throw fail("unknown header keyword '" + std::string(w[0]) + "'");
    }
  }
  if (!seen_format) throw SceneError(path + ": the PLY header has no format line");
  for (const PlyElement& element : header.elements) {
    // Reading instances of nothing would loop `count` times without consuming a byte.
    if (element.count > 0 && element.properties.empty()) {
      throw SceneError(path + ": line " + std::to_string(element.header_line) + ": element '" +
                       element.name + "' has instances but no properties");
    }
  }
  header.body_offset = pos;
  header.body_line = line_number + 1;
  return header;
}

// Text body: whitespace-separated numbers; element boundaries are not tied to lines.
class AsciiBody {
 public:
  AsciiBody(std::string_view data, size_t offset, size_t first_line)
      : p_(data.data() + offset), end_(data.data() + data.size()), line_(first_line) {}

  // Every value comes back as a double, which holds every PLY integer exactly.
  bool read(PlyType type, double* value) {
    if (!next_token()) return false;
    const char* token_end = p_;
    while (token_end < end_ && !is_space(*token_end)) ++token_end;
    std::from_chars_result result;
    if (is_integer(type)) {
      int64_t i = 0;
      result = std::from_chars(p_, token_end, i);
      *value = static_cast<double>(i);
    } else {
      result = std::from_chars(p_, token_end, *value);
    }
    const bool ok = result.ec == std::errc() && result.ptr == token_end;
    p_ = token_end;
    return ok;
  }
  bool skip(PlyType) {
    if (!next_token()) return false;
    while (p_ < end_ && !is_space(*p_)) ++p_;
    return true;
  }
  // Whether `values` more numbers can follow: each takes a digit and a separator, except
  // that the last in the file needs no separator.
  bool can_hold(size_t values, PlyType) const {
    return values <= (static_cast<size_t>(end_ - p_) + 1) / 2;
  }
  std::string where() const { return "line " + std::to_string(line_); }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  bool next_token() {
    while (p_ < end_ && is_space(*p_)) {
      if (*p_ == '\n') ++line_;
      ++p_;
    }
    return p_ < end_;
  }

  const char* p_;
  const char* end_;
  size_t line_;
};

class BinaryBody {
 public:
  BinaryBody(std::string_view data, size_t offset, bool big_endian)
      : begin_(data.data()),
        p_(data.data() + offset),
        end_(data.data() + data.size()),
        swap_(big_endian != (std::endian::native == std::endian::big)) {}

  bool read(PlyType type, double* value) {
    const size_t n = type_size(type);
    if (static_cast<size_t>(end_ - p_) < n) return false;
    unsigned char bytes[8] = {};
    for (size_t k = 0; k < n && k < sizeof bytes; ++k) {
      bytes[k] = static_cast<unsigned char>(p_[swap_ ? n - 1 - k : k]);
    }
    p_ += n;
    *value = decode(type, bytes);
    return true;
  }
  bool skip(PlyType type) {
    const size_t n = type_size(type);
    if (static_cast<size_t>(end_ - p_) < n) return false;
    p_ += n;
    return true;
  }
  bool can_hold(size_t values, PlyType type) const {
    return values <= static_cast<size_t>(end_ - p_) / type_size(type);
  }
  std::string where() const { return "byte " + std::to_string(p_ - begin_); }

 private:
  template <typename T>
  static double as(const unsigned char* bytes) {
    T v;
    std::memcpy(&v, bytes, sizeof v);
    return static_cast<double>(v);
  }
  static double decode(PlyType type, const unsigned char* bytes) {
    switch (type) {
      case PlyType::kInt8:
        return as<int8_t>(bytes);
      case PlyType::kUint8:
        return as<uint8_t>(bytes);
      case PlyType::kInt16:
        return as<int16_t>(bytes);
      case PlyType::kUint16:
        return as<uint16_t>(bytes);
      case PlyType::kInt32:
        return as<int32_t>(bytes);
      case PlyType::kUint32:
        return as<uint32_t>(bytes);
      case PlyType::kFloat32:
        return as<float>(bytes);
      case PlyType::kFloat64:
        return as<double>(bytes);
    }
    return 0;
  }

  const char* begin_;
  const char* p_;
  const char* end_;
  bool swap_;
};

// What the vertex and face elements mean to us: which property holds x, y, z and which list
// holds the corner indices.
struct MeshLayout {
  size_t vertex_element = 0, face_element = 0;
  // Per vertex property: 0..2 for x..z, 3..5 for the normal's nx..nz, 6..7 for the texture
  // coordinates, -1 otherwise.
  std::vector<int> coordinate_of;
  bool normals = false;  // nx, ny and nz are all there
  bool uvs = false;      // both texture coordinates are there
  size_t index_property = 0;
};

MeshLayout find_layout(const std::string& path, const PlyHeader& header) {
  MeshLayout layout;
  std::optional<size_t> vertex, face;
  for (size_t e = 0; e < header.elements.size(); ++e) {
    if (header.elements[e].name == "vertex") vertex = e;
    if (header.elements[e].name == "face") face = e;
  }
  if (!vertex) throw SceneError(path + ": the PLY header declares no 'vertex' element");
  if (!face) throw SceneError(path + ": the PLY header declares no 'face' element");
  layout.vertex_element = *vertex;
  layout.face_element = *face;

  const std::vector<PlyProperty>& vertex_props = header.elements[*vertex].properties;
  layout.coordinate_of.assign(vertex_props.size(), -1);
  bool has[8] = {false, false, false, false, false, false, false, false};
  for (size_t i = 0; i < vertex_props.size(); ++i) {
    const std::string& name = vertex_props[i].name;
    const int axis = name == "x"    ? 0
                     : name == "y"  ? 1
                     : name == "z"  ? 2
                     : name == "nx" ? 3
                     : name == "ny" ? 4
                     : name == "nz" ? 5
                     // The names writers use for texture coordinates (Blender: s, t).
                     : name == "u" || name == "s" || name == "texture_u" || name == "texture_s" ? 6
                     : name == "v" || name == "t" || name == "texture_v" || name == "texture_t"
                         ? 7
                         : -1;
    if (axis < 0) continue;
    if (vertex_props[i].is_list) {
      throw SceneError(path + ": vertex property '" + name + "' is a list (expected a number)");
    }
    layout.coordinate_of[i] = axis;
    has[axis] = true;
  }
  if (!has[0] || !has[1] || !has[2]) {
    throw SceneError(path + ": the vertex element lacks one of the properties x, y, z");
  }
  // A normal needs all three components; a partial one is ignored (flat shading).
  layout.normals = has[3] && has[4] && has[5];
  layout.uvs = has[6] && has[7];
  for (int& axis : layout.coordinate_of) {
    if ((!layout.normals && axis >= 3 && axis < 6) || (!layout.uvs && axis >= 6)) axis = -1;
  }

  const std::vector<PlyProperty>& face_props = header.elements[*face].properties;
  bool found = false;
  for (size_t i = 0; i < face_props.size(); ++i) {
    if (face_props[i].name == "vertex_indices" || face_props[i].name == "vertex_index") {
      if (!face_props[i].is_list || !is_integer(face_props[i].type)) {
        throw SceneError(path + ": face property '" + face_props[i].name +
                         "' must be a list of integers");
      }
      layout.index_property = i;
      found = true;
    }
  }
  if (!found) {
    throw SceneError(path +
                     ": the face element has no list property vertex_indices or vertex_index");
  }
  return layout;
}

// Bytes a value of `type` takes at the least: binary, its size; text, a digit and a separator.
size_t min_value_bytes(PlyFormat format, PlyType type) {
  return format == PlyFormat::kAscii ? 2 : type_size(type);
}

// Rejects counts that the body cannot hold before anything is allocated for them, so that a
// header of a few bytes cannot ask for gigabytes. Every list is taken as empty except the
// face's index list, which needs its three corners.
void check_counts_fit(const std::string& path, const PlyHeader& header, const MeshLayout& layout,
                      size_t body_bytes) {
  // Corner indices are 32-bit, in our meshes as in Embree.
  constexpr uint64_t kMaxVertices = uint64_t{1} << 32;
  const PlyElement& vertices = header.elements[layout.vertex_element];
  if (vertices.count > kMaxVertices) {
    throw SceneError(path + ": line " + std::to_string(vertices.header_line) + ": " +
                     std::to_string(vertices.count) + " vertices, more than the " +
                     std::to_string(kMaxVertices) + " a mesh may have");
  }
  // The last value of a text body needs no separator after it.
  const uint64_t available = body_bytes + (header.format == PlyFormat::kAscii ? 1 : 0);
  uint64_t needed = 0;
  for (size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    uint64_t instance_bytes = 0;
    for (size_t p = 0; p < element.properties.size(); ++p) {
      const PlyProperty& property = element.properties[p];
      if (!property.is_list) {
        instance_bytes += min_value_bytes(header.format, property.type);
        continue;
      }
      instance_bytes += min_value_bytes(header.format, property.count_type);
      if (e == layout.face_element && p == layout.index_property) {
        instance_bytes += 3 * min_value_bytes(header.format, property.type);
      }
    }
    needed = saturating_add(needed, saturating_multiply(element.count, instance_bytes));
    if (needed > available) {
      throw SceneError(path + ": line " + std::to_string(element.header_line) + ": " +
                       std::to_string(element.count) + " instances of element '" + element.name +
                       "' (with the elements before it) need at least " + format_bytes(needed) +
                       " of body, but the file has " + format_bytes(body_bytes) +
                       " after its header");
    }
  }
}

template <typename Body>
TriangleMesh read_body(const std::string& path, const PlyHeader& header, const MeshLayout& layout,
                       const MemoryBudget& budget, Body body) {
  const size_t vertex_count = header.elements[layout.vertex_element].count;
  const size_t face_count = header.elements[layout.face_element].count;
  // A triangle per face; polygons grow the index array as they come, by no more than the
  // corners they add to the file.
  const uint64_t array_bytes =
      saturating_add(saturating_multiply(vertex_count, (layout.normals ? 2 : 1) * sizeof(Vec3) +
                                                           (layout.uvs ? sizeof(Uv) : 0)),
                     saturating_multiply(face_count, 3 * sizeof(uint32_t)));
  if (!budget.allows(array_bytes)) {
    throw SceneError(path + ": " +
                     budget.exceeded("the arrays of " + std::to_string(vertex_count) +
                                         " vertices and " + std::to_string(face_count) + " faces",
                                     array_bytes));
  }
  TriangleMesh mesh;
  mesh.positions.resize(vertex_count);
  if (layout.normals) mesh.normals.resize(vertex_count);
  if (layout.uvs) mesh.uvs.resize(vertex_count);
  mesh.indices.reserve(3 * face_count);
  std::vector<uint32_t> corners;

  for (size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    auto fail = [&](size_t instance, const std::string& what) -> SceneError {
      return SceneError(path + ": " + body.where() + " (" + element.name + " " +
                        std::to_string(instance) + "): " + what);
    };
    for (size_t i = 0; i < element.count; ++i) {
      for (size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        if (!property.is_list) {
          const bool wanted = e == layout.vertex_element && layout.coordinate_of[p] >= 0;
          if (!wanted) {
            if (!body.skip(property.type)) throw fail(i, "unexpected end of file");
            continue;
          }
          double value;
          if (!body.read(property.type, &value) || !std::isfinite(static_cast<float>(value))) {
            throw fail(i, "expected a finite number for property '" + property.name + "'");
          }
          const int axis = layout.coordinate_of[p];
          const auto coordinate = static_cast<float>(value);
          if (axis < 3) {
            mesh.positions[i][axis] = coordinate;
          } else if (axis < 6) {
            mesh.normals[i][axis - 3] = coordinate;
          } else if (axis == 6) {
            mesh.uvs[i].u = coordinate;
          } else {
            // PLY's v, like OBJ's, grows up the image; snee's down from its top row.
            mesh.uvs[i].v = 1.0f - coordinate;
          }
          continue;
        }

        double count_value;
        if (!body.read(property.count_type, &count_value) || count_value < 0) {
          throw fail(i, "expected a non-negative list length for property '" + property.name + "'");
        }
        const auto count = static_cast<size_t>(count_value);
        if (!body.can_hold(count, property.type)) {
          throw fail(i, "a list of " + std::to_string(count) + " items for property '" +
                            property.name + "' is longer than the rest of the file");
        }
        const bool indices = e == layout.face_element && p == layout.index_property;
        if (!indices) {
          for (size_t k = 0; k < count; ++k) {
            if (!body.skip(property.type)) throw fail(i, "unexpected end of file");
          }
          continue;
        }
        if (count < 3) {
          throw fail(i, "face has " + std::to_string(count) + " vertices (expected at least 3)");
        }
        corners.resize(count);
        for (size_t k = 0; k < count; ++k) {
          double index;
          if (!body.read(property.type, &index)) throw fail(i, "expected a vertex index");
          if (index < 0 || index >= static_cast<double>(mesh.positions.size())) {
            throw fail(i, "vertex index " + std::to_string(static_cast<int64_t>(index)) +
                              " is out of range (the file has " +
                              std::to_string(mesh.positions.size()) + " vertices)");
          }
          corners[k] = static_cast<uint32_t>(index);
        }
        for (size_t k = 1; k + 1 < count; ++k) {
          mesh.indices.insert(mesh.indices.end(), {corners[0], corners[k], corners[k + 1]});
        }
      }
    }
  }
  if (mesh.indices.empty()) throw SceneError(path + ": the PLY file has no faces");
  normalize_vertex_normals(mesh, path);
  return mesh;
}

}  // namespace

TriangleMesh load_ply(const std::string& path, const MemoryBudget& budget) {
  const std::string data = read_input_file(path, "mesh", budget);
  const PlyHeader header = parse_header(path, data);
  const MeshLayout layout = find_layout(path, header);
  check_counts_fit(path, header, layout, data.size() - header.body_offset);
  if (header.format == PlyFormat::kAscii) {
    return read_body(path, header, layout, budget,
                     AsciiBody(data, header.body_offset, header.body_line));
  }
  return read_body(
      path, header, layout, budget,
      BinaryBody(data, header.body_offset, header.format == PlyFormat::kBinaryBigEndian));
}

}  // namespace snee
