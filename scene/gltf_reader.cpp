#include "scene/gltf_reader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <tuple>

#include "scene/input_file.h"
#include "scene/mesh_topology.h"
#include "scene/metals.h"
#include "scene/rgb_image_io.h"
#include "scene/scene_error.h"

namespace snee {

namespace {

namespace fs = std::filesystem;

// Relative indices of refraction the scene loader accepts for dielectrics (kIorRange there).
constexpr double kMaxIor = 1e3;

std::string indexed(const std::string& list, size_t i) {
  return list + "[" + std::to_string(i) + "]";
}

class GltfReader {
 public:
  GltfReader(std::string path, const MemoryBudget& budget)
      : path_(std::move(path)), budget_(budget) {}

  GltfAsset read(const Transform& placement) {
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

 private:
  [[noreturn]] void fail(const std::string& element, const std::string& message) const {
    throw SceneError(path_ + ": " + element + ": " + message);
  }

  void warn(const std::string& element, const std::string& message) {
    asset_.warnings.push_back(path_ + ": " + element + ": " + message);
  }

  // The file and every external buffer or image go through read_input_file (regular files
  // only, within the budget). An image's bytes are kept as they are (in tinygltf::Image::image)
  // and decoded by rgb_image_io.h only if a material uses it as a texture.
  void load_model() {
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

  std::vector<int> scene_roots() const {
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

  // --- materials ---

  // A member of a glTF extension object, as a number, with a default.
  double extension_number(const tinygltf::ExtensionMap& extensions, const std::string& extension,
                          const std::string& key, double fallback, const std::string& element,
                          double min, double max) const {
    const auto it = extensions.find(extension);
    if (it == extensions.end() || !it->second.Has(key)) return fallback;
    const tinygltf::Value& value = it->second.Get(key);
    const std::string where = element + ".extensions." + extension + "." + key;
    if (!value.IsNumber()) fail(where, "expected a number");
    const double x = value.GetNumberAsDouble();
    if (!(x >= min && x <= max)) {
      fail(where, "expected a number in [" + std::to_string(min) + ", " + std::to_string(max) +
                      "], got " + std::to_string(x));
    }
    return x;
  }

  Rgb extension_rgb(const tinygltf::ExtensionMap& extensions, const std::string& extension,
                    const std::string& key, Rgb fallback, const std::string& element) const {
    const auto it = extensions.find(extension);
    if (it == extensions.end() || !it->second.Has(key)) return fallback;
    const tinygltf::Value& value = it->second.Get(key);
    const std::string where = element + ".extensions." + extension + "." + key;
    if (!value.IsArray() || value.ArrayLen() != 3) fail(where, "expected 3 numbers");
    float c[3];
    for (int i = 0; i < 3; ++i) {
      const tinygltf::Value& x = value.Get(i);
      if (!x.IsNumber() || !(x.GetNumberAsDouble() >= 0 && x.GetNumberAsDouble() <= 1)) {
        fail(where + "[" + std::to_string(i) + "]", "expected a number in [0, 1]");
      }
      c[i] = static_cast<float>(x.GetNumberAsDouble());
    }
    return {c[0], c[1], c[2]};
  }

  static Rgb factor_rgb(const std::vector<double>& v, Rgb fallback) {
    if (v.size() < 3) return fallback;
    return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
  }

  void check_unit(const std::string& where, double x) const {
    if (!(x >= 0 && x <= 1)) fail(where, "expected a number in [0, 1], got " + std::to_string(x));
  }

  // The single-scattering albedo whose multiple-scattering albedo in a semi-infinite slab is
  // `multiscatter`, by the fit of Kulla and Conty ("Revisiting physically based shading at
  // Imageworks", 2017) that KHR_materials_volume_scatter names for this conversion.
  static float single_scatter_albedo(float multiscatter) {
    const float a = std::clamp(multiscatter, 0.0f, 1.0f);
    const float s = 4.09712f + 4.20863f * a - std::sqrt(9.59217f + 41.6808f * a + 17.7126f * a * a);
    return std::clamp(1.0f - s * s, 0.0f, 1.0f);
  }

  // The decoded image of a material's texture, as an index into GltfAsset::textures. glTF
  // stores base colour textures sRGB-encoded, as rgb_image_io.h takes 8- and 16-bit images.
  int texture_image(const tinygltf::TextureInfo& info, const std::string& where,
                    PixelValues values = PixelValues::kColour) {
    if (info.texCoord != 0) {
      fail(where, "texCoord " + std::to_string(info.texCoord) +
                      ": snee reads only the first set of texture coordinates (TEXCOORD_0)");
    }
    if (info.index < 0 || static_cast<size_t>(info.index) >= model_.textures.size()) {
      fail(where, "index " + std::to_string(info.index) + " names no texture (the file has " +
                      std::to_string(model_.textures.size()) + ")");
    }
    if (info.extensions.count("KHR_texture_transform") > 0) {
      warn(where, "KHR_texture_transform is ignored; the texture coordinates are used as given");
    }
    const std::string texture_element = indexed("textures", static_cast<size_t>(info.index));
    const tinygltf::Texture& texture = model_.textures[static_cast<size_t>(info.index)];
    if (texture.source < 0 || static_cast<size_t>(texture.source) >= model_.images.size()) {
      fail(texture_element,
           "has no source image snee can read (images in extensions such as "
           "KHR_texture_basisu are not read)");
    }
    Texture out;
    if (texture.sampler >= 0) {
      if (static_cast<size_t>(texture.sampler) >= model_.samplers.size()) {
        fail(texture_element, "sampler " + std::to_string(texture.sampler) +
                                  " names no sampler (the file has " +
                                  std::to_string(model_.samplers.size()) + ")");
      }
      const tinygltf::Sampler& sampler = model_.samplers[static_cast<size_t>(texture.sampler)];
      out.wrap_u = wrap_mode(sampler.wrapS);
      out.wrap_v = wrap_mode(sampler.wrapT);
    }
    const auto image_index = static_cast<size_t>(texture.source);
    const std::tuple key{image_index, out.wrap_u, out.wrap_v, values};
    const auto cached = texture_of_image_.find(key);
    if (cached != texture_of_image_.end()) return cached->second;
    const tinygltf::Image& image = model_.images[image_index];
    const std::string image_element = indexed("images", image_index);
    // The name stands for the image in messages, and its extension tells OpenImageIO the format.
    std::string name = path_ + ": " + image_element;
    if (!image.uri.empty() && !image.uri.starts_with("data:")) {
      name = (fs::path(path_).parent_path() / image.uri).lexically_normal().string();
    } else if (image.mimeType == "image/png" || image.uri.starts_with("data:image/png")) {
      name += ".png";
    } else if (image.mimeType == "image/jpeg" || image.uri.starts_with("data:image/jpeg")) {
      name += ".jpg";
    }
    try {
      out.image = decode_rgb_image(std::string(image.image.begin(), image.image.end()), name,
                                   "texture", budget_, values);
    } catch (const SceneError& e) {
      fail(texture_element, e.what());
    }
    asset_.textures.push_back(std::move(out));
    const int index = static_cast<int>(asset_.textures.size() - 1);
    texture_of_image_[key] = index;
    return index;
  }

  // tinygltf gives the GL enum, and -1 where the sampler leaves it to the default (REPEAT).
  static TextureWrap wrap_mode(int gl) {
    switch (gl) {
      case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
        return TextureWrap::kMirror;
      case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
        return TextureWrap::kClamp;
      default:
        return TextureWrap::kRepeat;
    }
  }

  // A dielectric's or conductor's GGX alpha, roughnessFactor^2, and its metallic-roughness
  // texture, whose green channel g gives alpha = (roughnessFactor g)^2 at a hit.
  void set_roughness(const tinygltf::PbrMetallicRoughness& pbr, const std::string& pbr_path,
                     float alpha, Material& surface) {
    surface.roughness = alpha;
    if (pbr.metallicRoughnessTexture.index < 0) return;
    surface.roughness_texture = texture_image(
        pbr.metallicRoughnessTexture, pbr_path + ".metallicRoughnessTexture", PixelValues::kData);
    surface.roughness_texture_squared = true;
  }

  void read_material(size_t index) {
    const tinygltf::Material& m = model_.materials[index];
    const std::string element = indexed("materials", index);
    GltfMaterial out;
    out.element = element;
    out.name = m.name.empty() ? element : m.name;
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    const std::string pbr_path = element + ".pbrMetallicRoughness";
    for (size_t i = 0; i < pbr.baseColorFactor.size(); ++i) {
      check_unit(pbr_path + ".baseColorFactor[" + std::to_string(i) + "]", pbr.baseColorFactor[i]);
    }
    check_unit(pbr_path + ".metallicFactor", pbr.metallicFactor);
    check_unit(pbr_path + ".roughnessFactor", pbr.roughnessFactor);
    if (m.normalTexture.index >= 0 || m.emissiveTexture.index >= 0 ||
        m.occlusionTexture.index >= 0) {
      warn(element,
           "normal, emissive and occlusion textures are ignored (snee reads base colour textures "
           "of diffuse materials and the roughness of metallic-roughness textures); the constant "
           "factors are used");
    }
    const Rgb base_color = factor_rgb(pbr.baseColorFactor, Rgb(1.0f));
    const float alpha = static_cast<float>(pbr.roughnessFactor * pbr.roughnessFactor);
    const double transmission = extension_number(m.extensions, "KHR_materials_transmission",
                                                 "transmissionFactor", 0, element, 0, 1);
    if (transmission > 0) {
      if (transmission < 1) {
        warn(element, "transmissionFactor " + std::to_string(transmission) +
                          " is rendered as 1: snee has no blend of a transmitting and an opaque "
                          "surface, so any transmission makes a dielectric");
      }
      out.surface.kind = MaterialKind::kDielectric;
      out.surface.ior = static_cast<float>(
          extension_number(m.extensions, "KHR_materials_ior", "ior", 1.5, element, 1, kMaxIor));
      set_roughness(pbr, pbr_path, alpha, out.surface);
      const double thickness = extension_number(m.extensions, "KHR_materials_volume",
                                                "thicknessFactor", 0, element, 0, HUGE_VAL);
      if (thickness > 0) {
        const Rgb color = extension_rgb(m.extensions, "KHR_materials_volume", "attenuationColor",
                                        Rgb(1.0f), element);
        const double distance =
            extension_number(m.extensions, "KHR_materials_volume", "attenuationDistance", HUGE_VAL,
                             element, std::nextafter(0.0, 1.0), HUGE_VAL);
        // Beer-Lambert: the attenuation colour is the transmittance after attenuationDistance.
        Rgb sigma_t(0.0f);
        if (std::isfinite(distance)) {
          for (int c = 0; c < 3; ++c) {
            sigma_t[c] =
                static_cast<float>(-std::log(std::max(double{color[c]}, 1e-30)) / distance);
          }
          if (!is_finite(sigma_t)) {
            fail(element + ".extensions.KHR_materials_volume",
                 "attenuationColor and attenuationDistance give an attenuation beyond "
                 "single-precision range");
          }
        }
        Medium medium;
        medium.name = out.name;
        const auto scatter = m.extensions.find("KHR_materials_volume_scatter");
        if (scatter != m.extensions.end()) {
          const Rgb multiscatter = extension_rgb(m.extensions, "KHR_materials_volume_scatter",
                                                 "multiscatterColor", Rgb(0.0f), element);
          medium.g = static_cast<float>(
              extension_number(m.extensions, "KHR_materials_volume_scatter", "scatterAnisotropy", 0,
                               element, std::nextafter(-1.0, 0.0), std::nextafter(1.0, 0.0)));
          for (int c = 0; c < 3; ++c) {
            const float albedo = single_scatter_albedo(multiscatter[c]);
            medium.sigma_s[c] = albedo * sigma_t[c];
            medium.sigma_a[c] = sigma_t[c] - medium.sigma_s[c];
          }
        } else {
          // Core glTF volumes only absorb; scattering comes from the scene's "media" override.
          medium.sigma_s = Rgb(0.0f);
          medium.sigma_a = sigma_t;
        }
        out.interior = medium;
      } else {
        warn(element,
             "a transmitting material without KHR_materials_volume (or with thicknessFactor 0) "
             "is a thin wall in glTF; snee has no thin walls and renders it as the boundary of a "
             "solid dielectric");
      }
    } else if (pbr.metallicFactor >= 0.5) {
      if (pbr.metallicFactor < 1) {
        warn(element, "metallicFactor " + std::to_string(pbr.metallicFactor) +
                          " is rendered as 1: snee has no blend of a metal and a diffuse "
                          "surface, so a material at least half metallic is a conductor");
      }
      // The base colour is the normal-incidence reflectance, rising to white at grazing
      // angles as glTF's Schlick Fresnel does (scene/metals.h).
      const ComplexIor ior = complex_ior_from_reflectance(base_color);
      out.surface.kind = MaterialKind::kConductor;
      out.surface.conductor_eta = ior.eta;
      out.surface.conductor_k = ior.k;
      set_roughness(pbr, pbr_path, alpha, out.surface);
      if (pbr.baseColorTexture.index >= 0) {
        warn(element,
             "the base colour texture of a metal is ignored (snee's conductors have one "
             "colour); baseColorFactor is used");
      }
    } else {
      if (pbr.metallicFactor > 0) {
        warn(element, "metallicFactor " + std::to_string(pbr.metallicFactor) +
                          " is rendered as 0: snee has no blend of a metal and a diffuse "
                          "surface, so a material less than half metallic is diffuse");
      }
      out.surface.kind = MaterialKind::kDiffuse;
      out.surface.albedo = base_color;
      if (pbr.metallicRoughnessTexture.index >= 0) {
        warn(element, "the metallic-roughness texture of a diffuse material is ignored");
      }
      if (pbr.baseColorTexture.index >= 0) {
        out.surface.albedo_texture =
            texture_image(pbr.baseColorTexture, pbr_path + ".baseColorTexture");
      }
    }
    for (size_t i = 0; i < m.emissiveFactor.size(); ++i) {
      check_unit(element + ".emissiveFactor[" + std::to_string(i) + "]", m.emissiveFactor[i]);
    }
    const double strength = extension_number(m.extensions, "KHR_materials_emissive_strength",
                                             "emissiveStrength", 1, element, 0, kMaxBrightness);
    out.emission = factor_rgb(m.emissiveFactor, Rgb(0.0f)) * static_cast<float>(strength);
    if (!is_finite(out.emission)) {
      fail(element, "emissiveFactor times emissiveStrength is beyond single-precision range");
    }
    out.surface.name = out.name;
    asset_.materials.push_back(std::move(out));
  }

  // glTF's default material: white, fully metallic and rough. snee renders it white diffuse.
  int default_material() {
    if (default_material_ < 0) {
      GltfMaterial out;
      out.name = out.element = "default material";
      out.surface.name = out.name;
      out.surface.kind = MaterialKind::kDiffuse;
      out.surface.albedo = Rgb(1.0f);
      default_material_ = static_cast<int>(asset_.materials.size());
      asset_.materials.push_back(std::move(out));
    }
    return default_material_;
  }

  // --- nodes ---

  Transform local_transform(const tinygltf::Node& node, const std::string& element) const {
    Transform t;
    if (!node.matrix.empty()) {
      if (node.matrix.size() != 16) fail(element + ".matrix", "expected 16 numbers");
      for (int col = 0; col < 4; ++col) {
        for (int row = 0; row < 4; ++row) {
          const double x = node.matrix[4 * col + row];
          if (row < 3) {
            t.m[row][col] = static_cast<float>(x);
          } else if (x != (col == 3 ? 1.0 : 0.0)) {
            fail(element + ".matrix", "expected an affine matrix (last row 0, 0, 0, 1)");
          }
        }
      }
      return t;
    }
    if (!node.scale.empty()) {
      if (node.scale.size() != 3) fail(element + ".scale", "expected 3 numbers");
      t = Transform::scale(Vec3(static_cast<float>(node.scale[0]),
                                static_cast<float>(node.scale[1]),
                                static_cast<float>(node.scale[2])));
    }
    if (!node.rotation.empty()) {
      if (node.rotation.size() != 4) fail(element + ".rotation", "expected 4 numbers");
      double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
      const double norm = std::sqrt(x * x + y * y + z * z + w * w);
      if (!(norm > 0) || !std::isfinite(norm)) {
        fail(element + ".rotation", "expected a unit quaternion [x, y, z, w]");
      }
      x /= norm, y /= norm, z /= norm, w /= norm;
      Transform r;
      const double m[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                              {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                              {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) r.m[i][j] = static_cast<float>(m[i][j]);
      }
      t = r * t;
    }
    if (!node.translation.empty()) {
      if (node.translation.size() != 3) fail(element + ".translation", "expected 3 numbers");
      t = Transform::translate(Vec3(static_cast<float>(node.translation[0]),
                                    static_cast<float>(node.translation[1]),
                                    static_cast<float>(node.translation[2]))) *
          t;
    }
    return t;
  }

  void visit_node(int index, const Transform& parent) {
    if (index < 0 || static_cast<size_t>(index) >= model_.nodes.size()) {
      fail("nodes", "a scene or node refers to node " + std::to_string(index) +
                        " but the file has " + std::to_string(model_.nodes.size()));
    }
    const std::string element = indexed("nodes", static_cast<size_t>(index));
    if (visited_[index]) {
      fail(element,
           "is reached twice in the node hierarchy (a glTF node has at most one parent "
           "and no cycles)");
    }
    visited_[index] = true;
    const tinygltf::Node& node = model_.nodes[index];
    const Transform world = parent * local_transform(node, element);
    for (const auto& row : world.m) {
      if (!std::all_of(std::begin(row), std::end(row), [](float x) { return std::isfinite(x); })) {
        fail(element, "the node's world transform has entries beyond single-precision range");
      }
    }
    if (node.mesh >= 0) place_mesh(node, element, world);
    if (node.camera >= 0) place_camera(node, element, world);
    const auto light = node.extensions.find("KHR_lights_punctual");
    if (light != node.extensions.end()) place_light(light->second, element, world);
    for (const int child : node.children) visit_node(child, world);
  }

  void place_camera(const tinygltf::Node& node, const std::string& element,
                    const Transform& world) {
    if (static_cast<size_t>(node.camera) >= model_.cameras.size()) {
      fail(element + ".camera", "refers to camera " + std::to_string(node.camera) +
                                    " but the file has " + std::to_string(model_.cameras.size()));
    }
    if (asset_.camera) return;
    const std::string camera_element = indexed("cameras", static_cast<size_t>(node.camera));
    const tinygltf::Camera& c = model_.cameras[node.camera];
    if (c.type != "perspective") {
      fail(camera_element, "a '" + c.type + "' camera; snee has only perspective cameras");
    }
    const double fov_degrees = c.perspective.yfov * 180.0 / M_PI;
    if (!(fov_degrees > 0 && fov_degrees < 180)) {
      fail(camera_element + ".perspective.yfov", "expected an angle in (0, pi) radians");
    }
    // A glTF camera looks down its local -z with +y up.
    Camera camera;
    camera.position = world.point(Vec3(0.0f));
    const Vec3 forward = normalize(world.vector(Vec3(0, 0, -1)));
    camera.look_at = camera.position + forward;
    camera.up = normalize(world.vector(Vec3(0, 1, 0)));
    camera.fov_degrees = static_cast<float>(fov_degrees);
    if (!is_finite(forward) || !is_finite(camera.up) ||
        !(length(cross(forward, camera.up)) > 1e-4f)) {
      fail(element, "the node's transform leaves the camera no viewing and up direction");
    }
    asset_.camera = camera;
    asset_.camera_aspect = static_cast<float>(c.perspective.aspectRatio);
  }

  void place_light(const tinygltf::Value& extension, const std::string& element,
                   const Transform& world) {
    const std::string where = element + ".extensions.KHR_lights_punctual.light";
    if (!extension.Has("light") || !extension.Get("light").IsInt()) {
      fail(where, "expected the index of a light");
    }
    const int index = extension.Get("light").GetNumberAsInt();
    if (index < 0 || static_cast<size_t>(index) >= model_.lights.size()) {
      fail(where, "refers to light " + std::to_string(index) + " but the file has " +
                      std::to_string(model_.lights.size()));
    }
    const std::string light_element =
        indexed("extensions.KHR_lights_punctual.lights", static_cast<size_t>(index));
    const tinygltf::Light& l = model_.lights[index];
    for (size_t i = 0; i < l.color.size(); ++i) {
      check_unit(light_element + ".color[" + std::to_string(i) + "]", l.color[i]);
    }
    if (!(l.intensity >= 0 && l.intensity <= kMaxBrightness)) {
      fail(light_element + ".intensity", "expected a number in [0, 1e30]");
    }
    const Rgb power = factor_rgb(l.color, Rgb(1.0f)) * static_cast<float>(l.intensity);
    Light light;
    if (l.type == "directional") {
      // glTF lights shine down their local -z; snee's direction points toward the light. Lux
      // is irradiance on a surface facing the light.
      light.kind = LightKind::kDirectional;
      light.direction = normalize(world.vector(Vec3(0, 0, 1)));
      light.irradiance = power;
      if (!is_finite(light.direction)) fail(element, "the node's transform has no direction");
    } else if (l.type == "point") {
      // Candela: intensity, as snee's point light takes it. `range` is a hint for culling that
      // glTF lets renderers ignore; snee lights are never cut off.
      light.kind = LightKind::kPoint;
      light.position = world.point(Vec3(0.0f));
      light.intensity = power;
    } else if (l.type == "spot") {
      // Candela on the axis, which is the node's local -z. glTF's cone angles are half-angles
      // from the axis with 0 <= inner < outer <= pi/2; snee's falloff between them is a
      // smoothstep in the cosine (pbrt's), where glTF suggests a squared linear ramp.
      const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
      if (!(outer > 0 && outer <= kPi / 2 + 1e-6)) {
        fail(light_element + ".spot.outerConeAngle", "expected an angle in (0, pi/2]");
      }
      if (!(inner >= 0 && inner < outer)) {
        fail(light_element + ".spot.innerConeAngle", "expected an angle in [0, outerConeAngle)");
      }
      light.kind = LightKind::kSpot;
      light.position = world.point(Vec3(0.0f));
      light.intensity = power;
      light.spot_axis = normalize(world.vector(Vec3(0, 0, -1)));
      light.spot_cos_outer = static_cast<float>(std::cos(outer));
      light.spot_cos_inner = static_cast<float>(std::cos(inner));
      if (!is_finite(light.spot_axis)) fail(element, "the node's transform has no direction");
    } else {
      fail(light_element, "a '" + l.type +
                              "' light; KHR_lights_punctual defines directional, "
                              "point and spot lights");
    }
    asset_.lights.push_back(light);
  }

  // --- meshes ---

  struct AccessorView {
    const unsigned char* data = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int component_type = 0;
    int components = 0;
    bool normalized = false;
  };

  static int component_bytes(int type) {
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

  // The accessor's elements inside their buffer, checked to lie within it. `types` lists the
  // accepted (componentType, normalized) pairs and `wanted` says them in the message.
  AccessorView view(int index, const std::string& what, int components,
                    std::initializer_list<std::pair<int, bool>> types, const std::string& wanted) {
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

  static float component(const AccessorView& view, size_t i, int c) {
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

  static uint32_t index_at(const AccessorView& view, size_t i) {
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

  std::vector<Vec3> read_vec3s(const AccessorView& view, const std::string& element,
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

  TriangleMesh read_primitive(const tinygltf::Primitive& p, const std::string& element) {
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
      fail(element,
           budget_.exceeded("the arrays of " + std::to_string(positions.count) + " vertices and " +
                                std::to_string(corner_count) + " corners",
                            bytes));
    }
    TriangleMesh mesh;
    mesh.positions = read_vec3s(positions, element, "POSITION");
    mesh.indices.resize(corner_count);
    for (size_t i = 0; i < corner_count; ++i) {
      mesh.indices[i] = indices ? index_at(*indices, i) : static_cast<uint32_t>(i);
      if (mesh.indices[i] >= positions.count) {
        fail(element, "index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
                          " but the primitive has " + std::to_string(positions.count) +
                          " vertices");
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

  void place_mesh(const tinygltf::Node& node, const std::string& node_element,
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

  std::string path_;
  MemoryBudget budget_;
  tinygltf::Model model_;
  GltfAsset asset_;
  // (glTF image index, wrap modes) -> index into asset_.textures
  std::map<std::tuple<size_t, TextureWrap, TextureWrap, PixelValues>, int> texture_of_image_;
  std::vector<bool> visited_;
  int default_material_ = -1;
};

}  // namespace

GltfAsset load_gltf(const std::string& path, const Transform& placement,
                    const MemoryBudget& budget) {
  return GltfReader(path, budget).read(placement);
}

int find_gltf_material(const GltfAsset& asset, const std::string& name) {
  for (size_t i = 0; i < asset.materials.size(); ++i) {
    if (asset.materials[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace snee
