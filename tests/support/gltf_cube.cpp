#include "tests/support/gltf_cube.h"

#include <cstdint>
#include <vector>

namespace snee::test {

using nlohmann::json;

namespace {

template <typename T>
void append(std::string& bytes, const T& value) {
  bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
}

std::string padded(std::string s, char pad) {
  while (s.size() % 4 != 0) s += pad;
  return s;
}

}  // namespace

std::string base64(const std::string& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) n |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) n |= static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[n & 63] : '=';
  }
  return out;
}

CubeBuffer cube_buffer() {
  CubeBuffer cube;
  std::vector<float> positions, normals;
  std::vector<uint16_t> indices;
  for (int axis = 0; axis < 3; ++axis) {
    for (const float side : {-1.0f, 1.0f}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const uint16_t first = static_cast<uint16_t>(positions.size() / 3);
      const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& c : corners) {
        float p[3], n[3] = {0, 0, 0};
        p[axis] = 0.5f * side;
        p[u] = 0.5f * c[0];
        p[v] = 0.5f * c[1];
        n[axis] = side;
        positions.insert(positions.end(), p, p + 3);
        normals.insert(normals.end(), n, n + 3);
      }
      // (u, v, axis) is right-handed, so corners in that order face +axis.
      const uint16_t plus[6] = {0, 1, 2, 0, 2, 3}, minus[6] = {0, 2, 1, 0, 3, 2};
      for (const uint16_t k : side > 0 ? plus : minus) indices.push_back(first + k);
    }
  }
  for (const float x : positions) append(cube.bytes, x);
  cube.normals_offset = cube.bytes.size();
  for (const float x : normals) append(cube.bytes, x);
  cube.uvs_offset = cube.bytes.size();
  for (size_t i = 0; i < positions.size() / 3; ++i) {
    append(cube.bytes, static_cast<float>(i % 2));
    append(cube.bytes, static_cast<float>((i / 2) % 2));
  }
  cube.indices_offset = cube.bytes.size();
  for (const uint16_t i : indices) append(cube.bytes, i);
  return cube;
}

json cube_document(const CubeBuffer& cube, const std::string& buffer_uri) {
  json buffer = {{"byteLength", cube.bytes.size()}};
  if (!buffer_uri.empty()) buffer["uri"] = buffer_uri;
  return {{"asset", {{"version", "2.0"}}},
          {"extensionsUsed",
           {"KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
            "KHR_materials_volume"}},
          {"scene", 0},
          {"scenes", {{{"nodes", {0, 2, 3, 4}}}}},
          {"nodes",
           {{{"name", "holder"}, {"translation", {0, 0, -3}}, {"children", {1}}},
            {{"name", "cube"}, {"scale", {2, 2, 2}}, {"mesh", 0}},
            {{"name", "eye"}, {"camera", 0}},
            // A rotation by -90 degrees about x turns local -z into -y.
            {{"name", "sun"},
             {"rotation", {-std::sqrt(0.5), 0, 0, std::sqrt(0.5)}},
             {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
            {{"name", "bulb"},
             {"translation", {0, 4, 0}},
             {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}}}},
          {"cameras",
           {{{"type", "perspective"},
             {"perspective", {{"yfov", 0.5}, {"aspectRatio", 2.0}, {"znear", 0.1}}}}}},
          {"extensions",
           {{"KHR_lights_punctual",
             {{"lights",
               {{{"type", "directional"}, {"color", {1, 0.5, 0.25}}, {"intensity", 4}},
                {{"type", "point"}, {"intensity", 10}}}}}}}},
          {"meshes",
           {{{"name", "box"},
             {"primitives",
              {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
                {"indices", 3},
                {"material", 0}}}}}}},
          {"materials",
           {{{"name", "jade"},
             {"pbrMetallicRoughness",
              {{"baseColorFactor", {0.2, 0.8, 0.3, 1}},
               {"metallicFactor", 0},
               {"roughnessFactor", 0.5}}},
             {"extensions",
              {{"KHR_materials_transmission", {{"transmissionFactor", 1}}},
               {"KHR_materials_ior", {{"ior", 1.4}}},
               {"KHR_materials_volume",
                {{"thicknessFactor", 1},
                 {"attenuationColor", {0.5, 0.25, 1}},
                 {"attenuationDistance", 2}}}}}}}},
          {"buffers", {buffer}},
          {"bufferViews",
           {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", cube.normals_offset}},
            {{"buffer", 0},
             {"byteOffset", cube.normals_offset},
             {"byteLength", cube.uvs_offset - cube.normals_offset}},
            {{"buffer", 0},
             {"byteOffset", cube.uvs_offset},
             {"byteLength", cube.indices_offset - cube.uvs_offset}},
            {{"buffer", 0},
             {"byteOffset", cube.indices_offset},
             {"byteLength", cube.bytes.size() - cube.indices_offset}}}},
          {"accessors",
           {{{"bufferView", 0},
             {"componentType", 5126},
             {"count", 24},
             {"type", "VEC3"},
             {"min", {-0.5, -0.5, -0.5}},
             {"max", {0.5, 0.5, 0.5}}},
            {{"bufferView", 1}, {"componentType", 5126}, {"count", 24}, {"type", "VEC3"}},
            {{"bufferView", 2}, {"componentType", 5126}, {"count", 24}, {"type", "VEC2"}},
            {{"bufferView", 3}, {"componentType", 5123}, {"count", 36}, {"type", "SCALAR"}}}}};
}

std::string glb(const json& doc, const std::string& bin) {
  const std::string text = padded(doc.dump(), ' ');
  const std::string data = padded(bin, '\0');
  std::string out = "glTF";
  append(out, uint32_t{2});
  append(out, static_cast<uint32_t>(12 + 8 + text.size() + 8 + data.size()));
  append(out, static_cast<uint32_t>(text.size()));
  out += "JSON";
  out += text;
  append(out, static_cast<uint32_t>(data.size()));
  out += std::string("BIN\0", 4);
  out += data;
  return out;
}

}  // namespace snee::test
