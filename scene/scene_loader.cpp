#include "scene/scene_loader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <optional>

#include "scene/input_file.h"
#include "scene/scene_reader.h"

namespace snee {

namespace fs = std::filesystem;
using nlohmann::json;

namespace scene_reader {

LoadedScene SceneReader::read(const json& doc) {
  const JsonValue root(doc, "", origin_);
  const JsonObject top = root.object(
      {"name", "camera", "render", "materials", "media", "shapes", "lights", "include"});
  Scene& scene = out_.scene;
  scene.name = top.has("name") ? top.required("name").string() : fs::path(origin_).stem().string();
  if (auto camera = top.optional("camera")) read_camera(*camera);
  if (auto render = top.optional("render")) read_render(*render);
  if (auto materials = top.optional("materials")) {
    for (const JsonValue& m : materials->array()) add_material(m, true);
  }
  if (auto media = top.optional("media")) {
    for (const JsonValue& m : media->array()) add_medium(m, true);
  }
  if (auto lights = top.optional("lights")) {
    for (const JsonValue& l : lights->array()) read_light(l);
  }
  // Included assets come after the listed lights and before the listed shapes, in both the
  // document as written and its canonical form, so a reload keeps every index.
  std::optional<Camera> included_camera;
  if (auto includes = top.optional("include")) {
    canonical_["include"] = json::array();
    for (const JsonValue& include : includes->array()) {
      std::optional<Camera> camera = read_include(include);
      if (!included_camera) included_camera = camera;
    }
  }
  if (!top.has("camera")) {
    if (!included_camera) {
      root.fail("expected a camera: a \"camera\" object, or an included glTF file with one");
    }
    scene.camera = *included_camera;
    canonical_["camera"] = canonical_camera(scene.camera, scene.camera.up);
  }
  if (!top.has("shapes") && !top.has("include")) top.required("shapes");
  if (auto shapes = top.optional("shapes")) {
    for (const JsonValue& shape : shapes->array()) read_shape(shape);
  }
  // Area lights come after the listed lights, in shape order, so a reload of the canonical
  // document (which lists only the others) rebuilds the same light list.
  for (size_t i = 0; i < scene.shapes.size(); ++i) {
    if (is_black(scene.shapes[i].emission)) continue;
    Light light;
    light.kind = LightKind::kArea;
    light.shape = static_cast<int>(i);
    scene.lights.push_back(light);
  }
  check_volumes();

  canonical_["name"] = scene.name;
  canonical_["render"] = canonical_render();
  canonical_["materials"] = canonical_materials_;
  canonical_["media"] = canonical_media_;
  canonical_["shapes"] = canonical_shapes_;
  canonical_["lights"] = canonical_lights_;
  out_.canonical = std::move(canonical_);
  return std::move(out_);
}

SceneReader::ResolvedPath SceneReader::resolve(const std::string& name) const {
  const fs::path p(name);
  if (p.is_absolute()) return {p.lexically_normal().string(), p.lexically_normal().string()};
  if (name.starts_with(kDataPrefix)) {
    return {(fs::path(SNEE_DATA_DIR) / name.substr(kDataPrefix.size())).lexically_normal().string(),
            p.lexically_normal().string()};
  }
  const std::string file = fs::absolute(fs::path(base_dir_) / p).lexically_normal().string();
  return {file, file};
}

}  // namespace scene_reader

LoadedScene load_scene_json(const json& doc, const std::string& origin, const std::string& base_dir,
                            const MemoryBudget& budget) {
  return scene_reader::SceneReader(origin, base_dir, budget).read(doc);
}

LoadedScene load_scene_file(const std::string& path, const MemoryBudget& budget) {
  const std::string text = read_input_file(path, "the scene file", budget);
  return load_scene_json(parse_json_document(text, path), path,
                         fs::path(path).parent_path().string(), budget);
}

LoadedScene load_scene(const std::string& spec, const MemoryBudget& budget) {
  constexpr std::string_view kBuiltinPrefix = "builtin:";
  if (spec.starts_with(kBuiltinPrefix))
    return load_builtin_scene(spec.substr(kBuiltinPrefix.size()));
  std::string ext = fs::path(spec).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".gltf" || ext == ".glb") {
    // A glTF file alone is the scene that includes it, with its camera and lights.
    const json doc = {{"name", fs::path(spec).stem().string()},
                      {"include", json::array({{{"file", fs::absolute(spec).string()}}})}};
    return load_scene_json(doc, spec, fs::path(spec).parent_path().string(), budget);
  }
  return load_scene_file(spec, budget);
}

}  // namespace snee
