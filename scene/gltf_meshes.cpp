// A glTF asset's triangle meshes, read through accessors checked to lie within their buffers.
#include <cmath>
#include <cstring>

#include "scene/gltf_model_reader.h"
#include "scene/mesh_topology.h"

namespace snee::gltf_reader {

int GltfReader::component_bytes(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

GltfReader::AccessorView GltfReader::view(int index, const std::string& what, int components,
                                          std::initializer_list<std::pair<int, bool>> types,
                                          const std::string& wanted) {
  if (index < 0 || static_cast<size_t>(index) >= model_.accessors.size()) {
    fail(what, "refers to accessor " + std::to_string(index) + " but the file has " +
                   std::to_string(model_.accessors.size()));
  }
  const std::string element = indexed("accessors", static_cast<size_t>(index));
  const tinygltf::Accessor& a = model_.accessors[index];
  const int type_components = a.type == TINYGLTF_TYPE_SCALAR ? 1
                              : a.type == TINYGLTF_TYPE_VEC2 ? 2
                              : a.type == TINYGLTF_TYPE_VEC3 ? 3
                                                             : 0;
  if (type_components != components) {
    fail(element, what + " needs " + wanted);
  }
  if (std::none_of(types.begin(), types.end(), [&](const std::pair<int, bool>& t) {
        return t.first == a.componentType && t.second == a.normalized;
      })) {
    fail(element, what + " needs " + wanted);
  }
  if (a.sparse.isSparse) fail(element, "sparse accessors are not supported");
  if (a.count == 0) fail(element, what + " has no elements");
  if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= model_.bufferViews.size()) {
    fail(element,
         "expected a bufferView (one of " + std::to_string(model_.bufferViews.size()) + ")");
  }
  const std::string view_element = indexed("bufferViews", static_cast<size_t>(a.bufferView));
  const tinygltf::BufferView& v = model_.bufferViews[a.bufferView];
  if (v.buffer < 0 || static_cast<size_t>(v.buffer) >= model_.buffers.size()) {
    fail(view_element, "refers to buffer " + std::to_string(v.buffer) + " but the file has " +
                           std::to_string(model_.buffers.size()));
  }
  const tinygltf::Buffer& buffer = model_.buffers[v.buffer];
  if (saturating_add(v.byteOffset, v.byteLength) > buffer.data.size()) {
    fail(view_element, "reaches past the end of buffer " + std::to_string(v.buffer) + " (" +
                           std::to_string(buffer.data.size()) + " bytes)");
  }
  const size_t element_bytes = static_cast<size_t>(components * component_bytes(a.componentType));
  const size_t stride = v.byteStride ? v.byteStride : element_bytes;
  if (stride < element_bytes) {
    fail(view_element, "byteStride " + std::to_string(stride) + " is below the " +
                           std::to_string(element_bytes) + "-byte element of " + element);
  }
  const uint64_t end = saturating_add(
      saturating_add(a.byteOffset, saturating_multiply(a.count - 1, stride)), element_bytes);
  if (end > v.byteLength) {
    fail(element, "its " + std::to_string(a.count) + " elements reach past the end of " +
                      view_element + " (" + std::to_string(v.byteLength) + " bytes)");
  }
  AccessorView out;
  out.data = buffer.data.data() + v.byteOffset + a.byteOffset;
  out.stride = stride;
  out.count = a.count;
  out.component_type = a.componentType;
  out.components = components;
  out.normalized = a.normalized;
  return out;
}

float GltfReader::component(const AccessorView& view, size_t i, int c) {
  const unsigned char* p = view.data + i * view.stride + c * component_bytes(view.component_type);
  switch (view.component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return static_cast<float>(*p) / 255.0f;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t x;
      std::memcpy(&x, p, sizeof x);
      return static_cast<float>(x) / 65535.0f;
    }
    default: {
      float x;
      std::memcpy(&x, p, sizeof x);
      return x;
    }
  }
}

uint32_t GltfReader::index_at(const AccessorView& view, size_t i) {
  const unsigned char* p = view.data + i * view.stride;
  switch (view.component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t x;
      std::memcpy(&x, p, sizeof x);
      return x;
    }
    default: {
      uint32_t x;
      std::memcpy(&x, p, sizeof x);
      return x;
    }
  }
}

std::vector<Vec3> GltfReader::read_vec3s(const AccessorView& view, const std::string& element,
                                         const std::string& what) const {
  std::vector<Vec3> out(view.count);
  for (size_t i = 0; i < view.count; ++i) {
    out[i] = Vec3(component(view, i, 0), component(view, i, 1), component(view, i, 2));
    if (!is_finite(out[i])) {
      fail(element, what + " " + std::to_string(i) + " has a component that is not finite");
    }
  }
  return out;
}

TriangleMesh GltfReader::read_primitive(const tinygltf::Primitive& p, const std::string& element) {
  if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1) {
    fail(element, "mode " + std::to_string(p.mode) +
                      " (points, lines, strips or fans); snee reads triangle lists (mode 4)");
  }
  const auto position = p.attributes.find("POSITION");
  if (position == p.attributes.end()) fail(element, "has no POSITION attribute");
  constexpr std::pair<int, bool> kFloat{TINYGLTF_COMPONENT_TYPE_FLOAT, false};
  const AccessorView positions =
      view(position->second, element + " POSITION", 3, {kFloat}, "VEC3 of FLOAT");
  std::optional<AccessorView> indices;
  if (p.indices >= 0) {
    indices = view(p.indices, element + " indices", 1,
                   {{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, false},
                    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, false},
                    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, false}},
                   "SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  }
  const size_t corner_count = indices ? indices->count : positions.count;
  if (corner_count % 3 != 0) {
    fail(element, std::to_string(corner_count) +
                      " triangle corners, not a multiple of 3 (a triangle list needs 3 each)");
  }
  const uint64_t bytes =
      saturating_add(saturating_multiply(positions.count, 2 * sizeof(Vec3) + sizeof(Uv)),
                     saturating_multiply(corner_count, sizeof(uint32_t)));
  if (!budget_.allows(bytes)) {
    fail(element, budget_.exceeded("the arrays of " + std::to_string(positions.count) +
                                       " vertices and " + std::to_string(corner_count) + " corners",
                                   bytes));
  }
  TriangleMesh mesh;
  mesh.positions = read_vec3s(positions, element, "POSITION");
  mesh.indices.resize(corner_count);
  for (size_t i = 0; i < corner_count; ++i) {
    mesh.indices[i] = indices ? index_at(*indices, i) : static_cast<uint32_t>(i);
    if (mesh.indices[i] >= positions.count) {
      fail(element, "index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
                        " but the primitive has " + std::to_string(positions.count) + " vertices");
    }
  }
  const auto normal = p.attributes.find("NORMAL");
  if (normal != p.attributes.end()) {
    const AccessorView normals =
        view(normal->second, element + " NORMAL", 3, {kFloat}, "VEC3 of FLOAT");
    if (normals.count != positions.count) {
      fail(element, "NORMAL has " + std::to_string(normals.count) + " elements, POSITION " +
                        std::to_string(positions.count));
    }
    mesh.normals = read_vec3s(normals, element, "NORMAL");
    for (Vec3& n : mesh.normals) n = normalize(n);
  }
  const auto texcoord = p.attributes.find("TEXCOORD_0");
  if (texcoord != p.attributes.end()) {
    const AccessorView uvs = view(texcoord->second, element + " TEXCOORD_0", 2,
                                  {kFloat,
                                   {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, true},
                                   {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, true}},
                                  "VEC2 of FLOAT, normalized UNSIGNED_BYTE or UNSIGNED_SHORT");
    if (uvs.count != positions.count) {
      fail(element, "TEXCOORD_0 has " + std::to_string(uvs.count) + " elements, POSITION " +
                        std::to_string(positions.count));
    }
    mesh.uvs.resize(uvs.count);
    for (size_t i = 0; i < uvs.count; ++i) {
      mesh.uvs[i] = {component(uvs, i, 0), component(uvs, i, 1)};
      if (!std::isfinite(mesh.uvs[i].u) || !std::isfinite(mesh.uvs[i].v)) {
        fail(element, "TEXCOORD_0 " + std::to_string(i) + " is not finite");
      }
    }
  }
  if (!p.targets.empty()) warn(element, "morph targets are ignored (the base shape is used)");
  return mesh;
}

void GltfReader::place_mesh(const tinygltf::Node& node, const std::string& node_element,
                            const Transform& world) {
  if (static_cast<size_t>(node.mesh) >= model_.meshes.size()) {
    fail(node_element + ".mesh", "refers to mesh " + std::to_string(node.mesh) +
                                     " but the file has " + std::to_string(model_.meshes.size()));
  }
  if (node.skin >= 0) warn(node_element, "skinning is ignored (the mesh is placed unskinned)");
  if (!(std::fabs(world.determinant()) > 0)) {
    warn(node_element, "the node's transform is singular (a zero scale); its mesh is skipped");
    return;
  }
  const tinygltf::Mesh& m = model_.meshes[node.mesh];
  for (size_t j = 0; j < m.primitives.size(); ++j) {
    const std::string element =
        indexed("meshes", static_cast<size_t>(node.mesh)) + "." + indexed("primitives", j);
    const tinygltf::Primitive& p = m.primitives[j];
    GltfPrimitive out;
    out.mesh = read_primitive(p, element);
    out.element = node_element + " " + element;
    out.name = !node.name.empty() ? node.name : !m.name.empty() ? m.name : element;
    if (p.material >= 0) {
      if (static_cast<size_t>(p.material) >= asset_.materials.size()) {
        fail(element + ".material", "refers to material " + std::to_string(p.material) +
                                        " but the file has " +
                                        std::to_string(model_.materials.size()));
      }
      out.material = p.material;
    } else {
      out.material = default_material();
    }
    apply_transform(world, out.mesh);
    if (world.determinant() < 0) flip_winding(out.mesh);
    asset_.primitives.push_back(std::move(out));
  }
}

}  // namespace snee::gltf_reader
