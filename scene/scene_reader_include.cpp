// The scene document's "include" list: glTF assets placed in the scene, their materials and media
// replaced by name where the document says so.
#include <algorithm>
#include <filesystem>
#include <optional>
#include <utility>

#include "scene/gltf_reader.h"
#include "scene/mesh_topology.h"
#include "scene/scene_reader.h"

namespace snee::scene_reader {

namespace fs = std::filesystem;
using nlohmann::json;

std::optional<Camera> SceneReader::read_include(const JsonValue& value) {
  const JsonObject obj =
      value.object({"file", "transform", "resolution", "materials", "media", "shading"});
  const JsonValue file_value = obj.required("file");
  const ResolvedPath file = resolve(file_value.string());
  const std::optional<JsonValue> transform_value = obj.optional("transform");
  const Transform transform = transform_value ? parse_transform(*transform_value) : Transform();
  GltfAsset asset;
  try {
    asset = load_gltf(file.file, transform, budget_);
  } catch (const SceneError& e) {
    file_value.fail(e.what());
  }
  for (std::string& warning : asset.warnings) out_.warnings.push_back(std::move(warning));
  json canonical = {{"file", file.canonical}, {"transform", to_json(transform)}};

  // Each glTF material's snee material and medium, by default the asset's own.
  const std::string prefix = fs::path(file.file).filename().string() + ":";
  std::vector<int> materials(asset.materials.size(), -1), media(asset.materials.size(), -1);
  auto override_target = [&](const JsonValue& key_value, const std::string& key) {
    const int index = find_gltf_material(asset, key);
    if (index < 0) {
      std::string names;
      for (const GltfMaterial& m : asset.materials)
        names += (names.empty() ? "'" : ", '") + m.name + "'";
      key_value.fail("the glTF file " + file.file + " has no material named '" + key +
                     "' (it has " + (names.empty() ? std::string("none") : names) + ")");
    }
    return index;
  };
  std::vector<bool> medium_overridden(asset.materials.size(), false);
  for (const char* list : {"materials", "media"}) {
    const std::optional<JsonValue> overrides = obj.optional(list);
    if (!overrides) continue;
    if (!overrides->json().is_object())
      overrides->expected("an object keyed by glTF material name");
    json canonical_overrides = json::object();
    for (const auto& [key, item] : overrides->json().items()) {
      const JsonValue item_value(item, json_child_path(overrides->path(), key), origin_);
      const int index = override_target(item_value, key);
      const bool is_material = std::string(list) == "materials";
      if (!is_material && item.is_null()) {
        medium_overridden[index] = true;
        canonical_overrides[key] = nullptr;
        continue;
      }
      const int target = reference(item_value, is_material);
      if (is_material) {
        materials[index] = target;
        canonical_overrides[key] = out_.scene.materials[target].name;
      } else {
        media[index] = target;
        medium_overridden[index] = true;
        canonical_overrides[key] = out_.scene.media[target].name;
      }
    }
    canonical[list] = canonical_overrides;
  }
  const int first_texture = static_cast<int>(out_.scene.textures.size());
  for (Texture& texture : asset.textures) out_.scene.textures.push_back(std::move(texture));
  for (size_t i = 0; i < asset.materials.size(); ++i) {
    GltfMaterial& m = asset.materials[i];
    if (materials[i] < 0) {
      m.surface.name = prefix + m.name;
      if (m.surface.albedo_texture >= 0) m.surface.albedo_texture += first_texture;
      if (m.surface.roughness_texture >= 0) m.surface.roughness_texture += first_texture;
      out_.scene.materials.push_back(m.surface);
      materials[i] = static_cast<int>(out_.scene.materials.size() - 1);
    }
    if (!medium_overridden[i] && m.interior) {
      m.interior->name = prefix + m.name;
      out_.scene.media.push_back(*m.interior);
      media[i] = static_cast<int>(out_.scene.media.size() - 1);
    }
  }

  // "smooth" is what a primitive with a NORMAL attribute gets anyway; one without stays flat.
  const std::optional<JsonValue> shading = obj.optional("shading");
  const bool flat = shading && shading->choice({"smooth", "flat"}) == "flat";
  if (shading) canonical["shading"] = flat ? "flat" : "smooth";
  for (GltfPrimitive& primitive : asset.primitives) {
    Shape shape;
    shape.name = primitive.name;
    shape.source = file.file + ": " + primitive.element;
    shape.mesh = std::move(primitive.mesh);
    shape.smooth_shading = !flat && !shape.mesh.normals.empty();
    check_mesh_coordinates(shape.mesh, value, shape.source);
    // glTF splits vertices where normals or texture coordinates differ, so whether the
    // surface is closed is asked of the positions, not of the vertex numbers.
    const EdgeCounts edges = count_edges(welded_by_position(shape.mesh));
    shape.closed = edges.boundary == 0;
    if (shape.closed && signed_volume(shape.mesh) < 0) flip_winding(shape.mesh);
    shape.material = materials[primitive.material];
    require_texture_coordinates(shape, value, "primitive " + shape.source, " (TEXCOORD_0)");
    shape.interior_medium = media[primitive.material];
    shape.emission = asset.materials[primitive.material].emission;
    if (shape.interior_medium >= 0) {
      const GltfMaterial& m = asset.materials[primitive.material];
      if (!bounds_media(out_.scene.materials[shape.material].kind)) {
        value.fail("the glTF material '" + m.name + "' (" + m.element +
                   ") has a volume but its snee material is opaque (diffuse, "
                   "diffuse_transmission or conductor), which light cannot enter; override its "
                   "medium with null or its material with a dielectric");
      }
      if (!shape.closed) {
        out_.warnings.push_back(shape.source + ": has an interior medium but is open (" +
                                std::to_string(edges.boundary) +
                                " boundary edges); paths inside may leak out through the holes");
      }
    }
    shape_places_.push_back(shape.source);
    out_.scene.shapes.push_back(std::move(shape));
  }
  for (const Light& light : asset.lights) out_.scene.lights.push_back(light);

  std::optional<Camera> camera = asset.camera;
  if (camera && asset.camera_aspect > 0) {
    camera->width = std::clamp(static_cast<int>(std::lround(camera->height * asset.camera_aspect)),
                               1, kMaxImageEdge);
  }
  if (auto resolution = obj.optional("resolution")) {
    const std::vector<JsonValue> wh = resolution->array(2);
    if (camera) {
      camera->width = static_cast<int>(wh[0].integer(1, kMaxImageEdge));
      camera->height = static_cast<int>(wh[1].integer(1, kMaxImageEdge));
    }
    canonical["resolution"] = resolution->json();
  }
  if (camera) {
    check_coordinates(camera->position, file_value, "the glTF camera position");
  }
  for (const Light& light : asset.lights) {
    if (light.kind == LightKind::kPoint || light.kind == LightKind::kSpot) {
      check_coordinates(light.position, file_value, "a glTF light position");
    }
  }
  canonical_["include"].push_back(canonical);
  return camera;
}

}  // namespace snee::scene_reader
