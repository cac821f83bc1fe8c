// The reader behind load_glTF (gltf_reader.h): one GltfReader per file, its parts implemented in
// gltf_reader.cpp (the file and its scene), gltf_materials.cpp, gltf_nodes.cpp and
// gltf_meshes.cpp. For those files only; everyone else calls gltf_reader.h.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <initializer_list>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "scene/gltf_reader.h"
#include "scene/rgb_image_io.h"
#include "scene/scene_error.h"

namespace snee::gltf_reader {

// Relative indices of refraction the scene loader accepts for dielectrics (kIorRange there).
inline constexpr double kMaxIor = 1e3;

inline std::string indexed(const std::string& list, size_t i) {
  return list + "[" + std::to_string(i) + "]";
}

class GltfReader {
 public:
  GltfReader(std::string path, const MemoryBudget& budget)
      : path_(std::move(path)), budget_(budget) {}

  GltfAsset read(const Transform& placement);

 private:
  [[noreturn]] void fail(const std::string& element, const std::string& message) const;
  void warn(const std::string& element, const std::string& message);

  // The file and every external buffer or image go through read_input_file (regular files
  // only, within the budget). An image's bytes are kept as they are (in tinygltf::Image::image)
  // and decoded by rgb_image_io.h only if a material uses it as a texture.
  void load_model();
  std::vector<int> scene_roots() const;

  // --- materials ---

  // A member of a glTF extension object, as a number, with a default.
  double extension_number(const tinygltf::ExtensionMap& extensions, const std::string& extension,
                          const std::string& key, double fallback, const std::string& element,
                          double min, double max) const;
  Rgb extension_rgb(const tinygltf::ExtensionMap& extensions, const std::string& extension,
                    const std::string& key, Rgb fallback, const std::string& element) const;
  static Rgb factor_rgb(const std::vector<double>& v, Rgb fallback);
  void check_unit(const std::string& where, double x) const;

  // The single-scattering albedo whose multiple-scattering albedo in a semi-infinite slab is
  // `multiscatter`, by the fit of Kulla and Conty ("Revisiting physically based shading at
  // Imageworks", 2017) that KHR_materials_volume_scatter names for this conversion.
  static float single_scatter_albedo(float multiscatter);

  // The decoded image of a material's texture, as an index into GltfAsset::textures. glTF
  // stores base colour textures sRGB-encoded, as rgb_image_io.h takes 8- and 16-bit images.
  int texture_image(const tinygltf::TextureInfo& info, const std::string& where,
                    PixelValues values = PixelValues::kColour);

  // tinygltf gives the GL enum, and -1 where the sampler leaves it to the default (REPEAT).
  static TextureWrap wrap_mode(int gl);

  // A dielectric's or conductor's GGX alpha, roughnessFactor^2, and its metallic-roughness
  // texture, whose green channel g gives alpha = (roughnessFactor g)^2 at a hit.
  void set_roughness(const tinygltf::PbrMetallicRoughness& pbr, const std::string& pbr_path,
                     float alpha, Material& surface);
  void read_material(size_t index);

  // glTF's default material: white, fully metallic and rough. snee renders it white diffuse.
  int default_material();

  // --- nodes ---

  Transform local_transform(const tinygltf::Node& node, const std::string& element) const;
  void visit_node(int index, const Transform& parent);
  void place_camera(const tinygltf::Node& node, const std::string& element, const Transform& world);
  void place_light(const tinygltf::Value& extension, const std::string& element,
                   const Transform& world);

  // --- meshes ---

  struct AccessorView {
    const unsigned char* data = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int component_type = 0;
    int components = 0;
    bool normalized = false;
  };
  static int component_bytes(int type);

  // The accessor's elements inside their buffer, checked to lie within it. `types` lists the
  // accepted (componentType, normalized) pairs and `wanted` says them in the message.
  AccessorView view(int index, const std::string& what, int components,
                    std::initializer_list<std::pair<int, bool>> types, const std::string& wanted);
  static float component(const AccessorView& view, size_t i, int c);
  static uint32_t index_at(const AccessorView& view, size_t i);
  std::vector<Vec3> read_vec3s(const AccessorView& view, const std::string& element,
                               const std::string& what) const;
  TriangleMesh read_primitive(const tinygltf::Primitive& p, const std::string& element);
  void place_mesh(const tinygltf::Node& node, const std::string& node_element,
                  const Transform& world);
  std::string path_;
  MemoryBudget budget_;
  tinygltf::Model model_;
  GltfAsset asset_;
  // (glTF image index, wrap modes) -> index into asset_.textures
  std::map<std::tuple<size_t, TextureWrap, TextureWrap, PixelValues>, int> texture_of_image_;
  std::vector<bool> visited_;
  int default_material_ = -1;
};

}  // namespace snee::gltf_reader
