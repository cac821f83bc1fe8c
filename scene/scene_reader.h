// The reader of snee's JSON scene format (docs/scene-format.md) behind load_scene_json: one
// SceneReader per document, its parts implemented in scene_loader.cpp (the document as a whole)
// and scene_reader_*.cpp (camera and render settings, included glTF assets, materials, media,
// shapes, lights). For those files only; everyone else calls scene_loader.h.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/density_grid.h"
#include "scene/json_reader.h"
#include "scene/metals.h"
#include "scene/rgb_image_io.h"
#include "scene/scene_json_values.h"
#include "scene/scene_loader.h"

namespace snee::scene_reader {

// Mesh and image paths starting with this prefix name files of the repository's data/ folder
// (SNEE_DATA_DIR), wherever the scene file lives.
inline constexpr std::string_view kDataPrefix = "data/";
inline constexpr int kSkyWidth = 128, kSkyHeight = 64;

class SceneReader {
 public:
  SceneReader(std::string origin, std::string base_dir, const MemoryBudget& budget)
      : origin_(std::move(origin)), base_dir_(std::move(base_dir)), budget_(budget) {}

  LoadedScene read(const nlohmann::json& doc);

 private:
  using json = nlohmann::json;
  // Absolute path of a mesh or image, and how the canonical document names it.
  struct ResolvedPath {
    std::string file;
    std::string canonical;
  };
  ResolvedPath resolve(const std::string& name) const;

  // scene_reader_camera.cpp
  void read_camera(const JsonValue& value);
  static void read_fov(const JsonValue& fov, Camera& camera);
  // After the focus distance: the ratio of the two sets the rays' spread.
  static void read_aperture(const JsonValue& aperture, Camera& camera);
  // Keys beyond the pinhole's only where they differ from their defaults, so that the document,
  // and with it the scene hash, of a scene without them stays what it was.
  static json canonical_camera(const Camera& camera, Vec3 up_as_given);
  void read_render(const JsonValue& value);
  json canonical_render() const;

  // scene_reader_include.cpp
  // A glTF asset placed in the scene: {"file", "transform", "resolution", "materials",
  // "media", "shading"}; "shading" applies to every primitive, as for a mesh shape. "materials" and
  // "media" map a glTF material's name to a snee material or medium (a defined name or an inline
  // definition; a medium may be null for none) that replaces what the asset's material gives.
  // Returns the asset's camera, with "resolution" applied.
  std::optional<Camera> read_include(const JsonValue& value);

  // scene_reader_materials.cpp
  // Definitions in the top-level lists must be named; one written inline in a shape may be, and
  // is otherwise named by the JSON path it sits at, which no sensible name collides with.
  std::string unique_name(const JsonObject& obj, bool top_level,
                          const std::map<std::string, std::string>& taken,
                          const std::string& kind) const;
  // A mesh whose material has a texture needs texture coordinates to look it up with (a sphere
  // has its own, surface_uv.h); `what` names the shape in the error at `where`.
  void require_texture_coordinates(const Shape& shape, const JsonValue& where,
                                   const std::string& what, const std::string& detail) const;
  // The texture read from `file`, read once however many materials use it as the same kind of
  // values; `where` is the JSON value naming it.
  int add_texture(const JsonValue& where, const std::string& file,
                  PixelValues values = PixelValues::kColour);
  // A dielectric's or conductor's `roughness` and `roughness_texture`. With a texture,
  // roughness is a factor on it (as glTF's roughnessFactor is), 1 by default.
  void add_roughness(const JsonObject& obj, Material& material, json& canonical);
  int add_material(const JsonValue& value, bool top_level);
  // A conductor's "metal" (a named index) or its "eta" and "k".
  static ComplexIor conductor_ior(const JsonObject& obj);
  // A shape's material or medium: the name of a defined one, or an inline definition.
  int reference(const JsonValue& value, bool is_material);

  // scene_reader_media.cpp
  // A grid medium's density: {"file": a .vol file} or {"resolution": [nx, ny, nz], "values":
  // [...]}, with "bounds": {"min": [x, y, z], "max": [x, y, z]} placing the grid in the world
  // (required for inline values; a file's own box otherwise).
  // `canonical` receives the density as the canonical scene writes it.
  DensityGrid density_grid(const JsonValue& value, json& canonical);
  // A medium's albedo from the image that `where` names: its mean colour, one albedo for the
  // whole medium (the medium stays homogeneous, as SNEE's samplers require).
  Rgb mean_albedo(const JsonValue& where);
  int add_medium(const JsonValue& value, bool top_level);

  // scene_reader_shapes.cpp
  // "shading" of a mesh: "smooth" (interpolated vertex normals; the default where the mesh has
  // them) or "flat". Recorded in the canonical form only for meshes with normals, where it
  // makes a difference.
  bool read_shading(const std::optional<JsonValue>& shading, const TriangleMesh& mesh,
                    const std::string& source, json& canonical) const;
  void read_shape(const JsonValue& value);
  // A path carries one medium at a time (docs/scene-format.md, "Several media").
  void check_volumes();

  // scene_reader_lights.cpp
  Transform read_rotation(const JsonValue& value);
  void read_light(const JsonValue& value);
  void read_spot(const JsonValue& value, Light& light, json& canonical);

  std::string origin_;
  std::string base_dir_;
  MemoryBudget budget_;
  LoadedScene out_;
  std::vector<std::string> shape_places_;              // shape index -> JSON path or glTF element
  std::map<std::string, std::string> material_names_;  // name -> JSON path of its definition
  std::map<std::string, std::string> medium_names_;
  // (file, what its pixels are) -> index into Scene::textures
  std::map<std::pair<std::string, PixelValues>, int> texture_files_;
  json canonical_ = json::object();
  json canonical_materials_ = json::array();
  json canonical_media_ = json::array();
  json canonical_shapes_ = json::array();
  json canonical_lights_ = json::array();
};

}  // namespace snee::scene_reader
