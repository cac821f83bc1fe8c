#include "scene/gltf_reader.h"

#include <filesystem>

#include "scene/gltf_model_reader.h"
#include "scene/input_file.h"

namespace snee {

namespace gltf_reader {

namespace fs = std::filesystem;

GltfAsset GltfReader::read(const Transform& placement) {
  load_model();
  for (size_t i = 0; i < model_.materials.size(); ++i) read_material(i);
  const std::vector<int> roots = scene_roots();
  visited_.assign(model_.nodes.size(), false);
  for (const int root : roots) visit_node(root, placement);
  if (asset_.primitives.empty()) {
    asset_.warnings.push_back(path_ + ": the scene places no triangle mesh");
  }
  return std::move(asset_);
}

void GltfReader::fail(const std::string& element, const std::string& message) const {
  throw SceneError(path_ + ": " + element + ": " + message);
}

void GltfReader::warn(const std::string& element, const std::string& message) {
  asset_.warnings.push_back(path_ + ": " + element + ": " + message);
}

void GltfReader::load_model() {
  const std::string bytes = read_input_file(path_, "glTF file", budget_);
  tinygltf::TinyGLTF loader;
  tinygltf::FsCallbacks fs_callbacks{};
  fs_callbacks.FileExists = [](const std::string& name, void*) {
    std::error_code error;
    return fs::is_regular_file(name, error);
  };
  fs_callbacks.ExpandFilePath = [](const std::string& name, void*) { return name; };
  fs_callbacks.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err,
                                  const std::string& name, void* user) {
    try {
      const std::string data =
          read_input_file(name, "glTF buffer", *static_cast<const MemoryBudget*>(user));
      out->assign(data.begin(), data.end());
      return true;
    } catch (const SceneError& e) {
      if (err) *err += e.what();
      return false;
    }
  };
  fs_callbacks.WriteWholeFile = [](std::string* err, const std::string&,
                                   const std::vector<unsigned char>&, void*) {
    if (err) *err += "snee never writes glTF files";
    return false;
  };
  fs_callbacks.user_data = const_cast<MemoryBudget*>(&budget_);
  loader.SetFsCallbacks(fs_callbacks);
  loader.SetImageLoader(
      [](tinygltf::Image* image, const int, std::string*, std::string*, int, int,
         const unsigned char* data, int size, void*) {
        image->image.assign(data, data + size);
        return true;
      },
      nullptr);
  std::string error, warning;
  const std::string base_dir = fs::path(path_).parent_path().string();
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(&model_, &error, &warning, data,
                                           static_cast<unsigned int>(bytes.size()), base_dir)
             : loader.LoadASCIIFromString(&model_, &error, &warning, bytes.data(),
                                          static_cast<unsigned int>(bytes.size()), base_dir);
  auto trimmed = [](std::string s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    return s;
  };
  if (!ok) {
    throw SceneError(path_ + ": cannot read glTF " + (binary ? "binary (.glb)" : "JSON") +
                     " file: " + trimmed(error.empty() ? warning : error));
  }
  if (!trimmed(warning).empty()) asset_.warnings.push_back(path_ + ": " + trimmed(warning));
  for (const std::string& required : model_.extensionsRequired) {
    static const std::vector<std::string> kKnown = {
        "KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
        "KHR_materials_volume", "KHR_materials_emissive_strength"};
    if (std::find(kKnown.begin(), kKnown.end(), required) == kKnown.end()) {
      fail("extensionsRequired",
           "the asset requires the extension " + required + ", which snee does not implement");
    }
  }
}

std::vector<int> GltfReader::scene_roots() const {
  if (model_.scenes.empty()) {
    fail("scenes", "the file has no scene, so nothing says which nodes to render");
  }
  const size_t scene = model_.defaultScene >= 0 ? static_cast<size_t>(model_.defaultScene) : 0;
  if (scene >= model_.scenes.size()) {
    fail("scene", "refers to scene " + std::to_string(scene) + " but the file has " +
                      std::to_string(model_.scenes.size()));
  }
  return model_.scenes[scene].nodes;
}

}  // namespace gltf_reader

GltfAsset load_gltf(const std::string& path, const Transform& placement,
                    const MemoryBudget& budget) {
  return gltf_reader::GltfReader(path, budget).read(placement);
}

int find_gltf_material(const GltfAsset& asset, const std::string& name) {
  for (size_t i = 0; i < asset.materials.size(); ++i) {
    if (asset.materials[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace snee
