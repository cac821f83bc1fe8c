// A glTF asset's materials as snee's (docs/scene-format.md has the table): base colour and its
// texture, metallic-roughness, transmission, volume, emission and their extensions.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "scene/gltf_model_reader.h"
#include "scene/metals.h"
#include "scene/rgb_image_io.h"

namespace snee::gltf_reader {

namespace fs = std::filesystem;

double GltfReader::extension_number(const tinygltf::ExtensionMap& extensions,
                                    const std::string& extension, const std::string& key,
                                    double fallback, const std::string& element, double min,
                                    double max) const {
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

Rgb GltfReader::extension_rgb(const tinygltf::ExtensionMap& extensions,
                              const std::string& extension, const std::string& key, Rgb fallback,
                              const std::string& element) const {
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

Rgb GltfReader::factor_rgb(const std::vector<double>& v, Rgb fallback) {
  if (v.size() < 3) return fallback;
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

void GltfReader::check_unit(const std::string& where, double x) const {
  if (!(x >= 0 && x <= 1)) fail(where, "expected a number in [0, 1], got " + std::to_string(x));
}

float GltfReader::single_scatter_albedo(float multiscatter) {
  const float a = std::clamp(multiscatter, 0.0f, 1.0f);
  const float s = 4.09712f + 4.20863f * a - std::sqrt(9.59217f + 41.6808f * a + 17.7126f * a * a);
  return std::clamp(1.0f - s * s, 0.0f, 1.0f);
}

int GltfReader::texture_image(const tinygltf::TextureInfo& info, const std::string& where,
                              PixelValues values) {
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

TextureWrap GltfReader::wrap_mode(int gl) {
  switch (gl) {
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
      return TextureWrap::kMirror;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
      return TextureWrap::kClamp;
    default:
      return TextureWrap::kRepeat;
  }
}

void GltfReader::set_roughness(const tinygltf::PbrMetallicRoughness& pbr,
                               const std::string& pbr_path, float alpha, Material& surface) {
  surface.roughness = alpha;
  if (pbr.metallicRoughnessTexture.index < 0) return;
  surface.roughness_texture = texture_image(
      pbr.metallicRoughnessTexture, pbr_path + ".metallicRoughnessTexture", PixelValues::kData);
  surface.roughness_texture_squared = true;
}

void GltfReader::read_material(size_t index) {
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
  if (m.normalTexture.index >= 0 || m.emissiveTexture.index >= 0 || m.occlusionTexture.index >= 0) {
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
          sigma_t[c] = static_cast<float>(-std::log(std::max(double{color[c]}, 1e-30)) / distance);
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

int GltfReader::default_material() {
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

}  // namespace snee::gltf_reader
