// Reading glTF 2.0 assets (.gltf with embedded or external buffers, and binary .glb) into snee's
// scene description: the default scene's node hierarchy with its transforms, triangle meshes
// (positions, indices, normals and texture coordinates), the first camera, KHR_lights_punctual
// lights and materials translated to snee's with their base colour textures (docs/scene-format.md
// has the table). Nothing here
// knows the JSON scene that includes the asset; scene_reader_include.cpp applies its overrides.
// Every failure is a SceneError "<file>: <glTF element>: <what is wrong>", e.g.
// "a.gltf: meshes[2].primitives[0]: the POSITION accessor 7 reaches past its buffer view".
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "scene/memory_budget.h"
#include "scene/scene.h"

namespace snee {

// One glTF material as snee reads it, before a scene's overrides.
struct GltfMaterial {
  std::string name;     // the material's name, or its element ("materials[3]") when unnamed
  std::string element;  // "materials[3]", or "default material" for primitives without one
  Material surface;     // albedo_texture indexes GltfAsset::textures
  std::optional<Medium> interior;  // KHR_materials_volume with a thickness, else none
  Rgb emission{0.0f};              // emissiveFactor times KHR_materials_emissive_strength
};

// One mesh primitive placed by one node, in world space.
struct GltfPrimitive {
  std::string name;     // the node's name, else the mesh's, else the element
  std::string element;  // "nodes[4] meshes[2].primitives[0]"
  TriangleMesh mesh;
  int material = 0;  // index into GltfAsset::materials
};

struct GltfAsset {
  std::vector<GltfMaterial> materials;
  std::vector<Texture> textures;  // decoded images, each once per sampler wrapping it
  std::vector<GltfPrimitive> primitives;
  std::vector<Light> lights;
  std::optional<Camera> camera;  // the first perspective camera met walking the scene
  float camera_aspect = 0;       // its aspectRatio, 0 when the file gives none
  std::vector<std::string> warnings;
};

// `placement` goes after the asset's own node transforms (it places the whole asset).
GltfAsset load_gltf(const std::string& path, const Transform& placement,
                    const MemoryBudget& budget = {});

// The first material of `asset` whose name is `name`, or -1.
int find_gltf_material(const GltfAsset& asset, const std::string& name);

}  // namespace snee
