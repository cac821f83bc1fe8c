// The scene document's materials (top-level or inline in a shape), their textures, and
// references to materials and media by name.
#include <map>
#include <optional>

#include "scene/metals.h"
#include "scene/rgb_image_io.h"
#include "scene/scene_reader.h"

namespace snee::scene_reader {

using nlohmann::json;

std::string SceneReader::unique_name(const JsonObject& obj, bool top_level,
                                     const std::map<std::string, std::string>& taken,
                                     const std::string& kind) const {
  std::optional<JsonValue> name_value =
      top_level ? std::optional(obj.required("name")) : obj.optional("name");
  const std::string name = name_value ? name_value->string() : obj.value().path();
  const auto it = taken.find(name);
  if (it != taken.end()) {
    (name_value ? *name_value : obj.value())
        .fail("the " + kind + " name '" + name + "' is already used by " + it->second);
  }
  return name;
}

void SceneReader::require_texture_coordinates(const Shape& shape, const JsonValue& where,
                                              const std::string& what,
                                              const std::string& detail) const {
  const Material& material = out_.scene.materials[static_cast<size_t>(shape.material)];
  if (!material.has_texture() || shape.kind == ShapeKind::kSphere || !shape.mesh.uvs.empty()) {
    return;
  }
  where.fail("the material '" + material.name + "' has a texture, but the " + what +
             " has no texture coordinates" + detail);
}

int SceneReader::add_texture(const JsonValue& where, const std::string& file, PixelValues values) {
  const auto it = texture_files_.find({file, values});
  if (it != texture_files_.end()) return it->second;
  try {
    out_.scene.textures.push_back({read_rgb_image(file, "texture", budget_, values)});
  } catch (const SceneError& e) {
    where.fail(e.what());
  }
  const int index = static_cast<int>(out_.scene.textures.size() - 1);
  texture_files_[{file, values}] = index;
  return index;
}

void SceneReader::add_roughness(const JsonObject& obj, Material& material, json& canonical) {
  const std::optional<JsonValue> texture = obj.optional("roughness_texture");
  if (texture) material.roughness = 1.0f;
  if (auto roughness = obj.optional("roughness")) {
    material.roughness = roughness->real(kUnitInterval);
  }
  canonical["roughness"] = material.roughness;
  if (texture) {
    const ResolvedPath file = resolve(texture->string());
    material.roughness_texture = add_texture(*texture, file.file, PixelValues::kData);
    canonical["roughness_texture"] = file.canonical;
  }
}

int SceneReader::add_material(const JsonValue& value, bool top_level) {
  const std::string type = value.member("type").choice(
      {"diffuse", "dielectric", "null", "conductor", "diffuse_transmission"});
  Material material;
  json canonical;
  if (type == "diffuse") {
    const JsonObject obj = value.object({"name", "type", "albedo", "albedo_texture"});
    material.name = unique_name(obj, top_level, material_names_, "material");
    material.kind = MaterialKind::kDiffuse;
    const std::optional<JsonValue> texture = obj.optional("albedo_texture");
    // With a texture, albedo is a factor on it (glTF's baseColorFactor), white by default.
    if (texture) material.albedo = Rgb(1.0f);
    if (auto albedo = obj.optional("albedo")) material.albedo = albedo->rgb(kUnitInterval);
    canonical = {{"albedo", to_json(material.albedo)}};
    if (texture) {
      const ResolvedPath file = resolve(texture->string());
      material.albedo_texture = add_texture(*texture, file.file);
      canonical["albedo_texture"] = file.canonical;
    }
  } else if (type == "dielectric") {
    const JsonObject obj = value.object({"name", "type", "ior", "roughness", "roughness_texture"});
    material.name = unique_name(obj, top_level, material_names_, "material");
    material.kind = MaterialKind::kDielectric;
    if (auto ior = obj.optional("ior")) material.ior = ior->real(kIorRange);
    canonical = {{"ior", material.ior}};
    add_roughness(obj, material, canonical);
  } else if (type == "conductor") {
    const JsonObject obj =
        value.object({"name", "type", "metal", "eta", "k", "roughness", "roughness_texture"});
    material.name = unique_name(obj, top_level, material_names_, "material");
    material.kind = MaterialKind::kConductor;
    const ComplexIor ior = conductor_ior(obj);
    material.conductor_eta = ior.eta;
    material.conductor_k = ior.k;
    canonical = {{"eta", to_json(material.conductor_eta)}, {"k", to_json(material.conductor_k)}};
    add_roughness(obj, material, canonical);
  } else if (type == "diffuse_transmission") {
    const JsonObject obj = value.object({"name", "type", "reflectance", "transmittance"});
    material.name = unique_name(obj, top_level, material_names_, "material");
    material.kind = MaterialKind::kDiffuseTransmission;
    material.albedo = material.transmittance = Rgb(0.5f);
    if (auto r = obj.optional("reflectance")) material.albedo = r->rgb(kUnitInterval);
    const std::optional<JsonValue> t = obj.optional("transmittance");
    if (t) material.transmittance = t->rgb(kUnitInterval);
    for (int c = 0; c < 3; ++c) {
      // Energy conservation, allowing the rounding of a value written as 1 - R.
      const float sum = material.albedo[c] + material.transmittance[c];
      if (sum > 1.0f + 1e-6f) {
        (t ? *t : obj.value())
            .fail("reflectance + transmittance is " + describe_number(sum) + " in channel " +
                  std::to_string(c) + (t ? "" : " (transmittance defaults to 0.5)") +
                  "; a sheet cannot scatter more light than it receives (expected at most 1)");
      }
    }
    canonical = {{"reflectance", to_json(material.albedo)},
                 {"transmittance", to_json(material.transmittance)}};
  } else {
    const JsonObject obj = value.object({"name", "type"});
    material.name = unique_name(obj, top_level, material_names_, "material");
    material.kind = MaterialKind::kNull;
    canonical = json::object();
  }
  canonical["name"] = material.name;
  canonical["type"] = type;
  canonical_materials_.push_back(canonical);
  material_names_[material.name] = value.path();
  out_.scene.materials.push_back(material);
  return static_cast<int>(out_.scene.materials.size() - 1);
}

ComplexIor SceneReader::conductor_ior(const JsonObject& obj) {
  if (auto metal = obj.optional("metal")) {
    if (obj.has("eta") || obj.has("k")) {
      obj.value().fail("give either metal or eta and k, not both");
    }
    if (metal->json().is_string()) {
      if (auto ior = find_metal(metal->string())) return *ior;
    }
    std::string names;
    for (std::string_view name : metal_names()) {
      names += (names.empty() ? "" : ", ") + std::string(name);
    }
    metal->expected("one of: " + names);
  }
  if (!obj.has("eta") || !obj.has("k")) {
    obj.value().fail("a conductor needs either metal (a named index) or both eta and k");
  }
  return {obj.required("eta").rgb(kConductorIndexRange),
          obj.required("k").rgb(kConductorIndexRange)};
}

int SceneReader::reference(const JsonValue& value, bool is_material) {
  if (value.json().is_object()) {
    return is_material ? add_material(value, false) : add_medium(value, false);
  }
  if (!value.json().is_string()) {
    value.expected(std::string("the name of a defined ") + (is_material ? "material" : "medium") +
                   " or an inline definition");
  }
  const std::string name = value.string();
  if (is_material) {
    for (size_t i = 0; i < out_.scene.materials.size(); ++i) {
      if (out_.scene.materials[i].name == name) return static_cast<int>(i);
    }
  } else {
    for (size_t i = 0; i < out_.scene.media.size(); ++i) {
      if (out_.scene.media[i].name == name) return static_cast<int>(i);
    }
  }
  value.fail(std::string("no ") + (is_material ? "material" : "medium") + " named '" + name +
             "' is defined");
}

}  // namespace snee::scene_reader
