#include "scene/scene_loader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "scene/camera_frame.h"
#include "scene/density_grid_io.h"
#include "scene/gltf_reader.h"
#include "scene/input_file.h"
#include "scene/json_reader.h"
#include "scene/mesh_io.h"
#include "scene/mesh_topology.h"
#include "scene/metals.h"
#include "scene/procedural_sky.h"
#include "scene/rgb_image_io.h"
#include "scene/volume_overlap.h"

namespace snee {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Mesh and image paths starting with this prefix name files of the repository's data/ folder
// (SNEE_DATA_DIR), wherever the scene file lives.
constexpr std::string_view kDataPrefix = "data/";
constexpr int kSkyWidth = 128, kSkyHeight = 64;
constexpr NumberRange kBrightness{0.0, kMaxBrightness};

json to_json(Vec3 v) {
  return json::array({v.x, v.y, v.z});
}

json to_json(const Transform& t) {
  json rows = json::array();
  for (const auto& row : t.m) rows.push_back(json::array({row[0], row[1], row[2], row[3]}));
  return json::array({json{{"matrix", rows}}});
}

// Relative indices of refraction beyond these are not materials; the bounds keep eta^2 and
// 1 / eta^2 of the Fresnel and radiance-scaling terms far from float's limits.
constexpr NumberRange kIorRange{1e-3, 1e3};
// A conductor's eta and k; 0 is allowed for both (eta = 0 with any k reflects everything).
constexpr NumberRange kConductorIndexRange{0.0, 1e3};
// The widest thin lens relative to its focus distance.
constexpr float kMaxApertureOverFocus = 1e6f;

float degrees_to_radians(float degrees) {
  return degrees * (kPi / 180.0f);
}

std::string describe_number(float x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

std::string describe_point(Vec3 p) {
  return "(" + describe_number(p.x) + ", " + describe_number(p.y) + ", " + describe_number(p.z) +
         ")";
}

std::string coordinate_bound_expectation() {
  return "expected every world-space coordinate within +-" + describe_number(kMaxCoordinate);
}

// False for NaN too.
bool within_coordinate_bound(Vec3 p) {
  return std::fabs(p.x) <= kMaxCoordinate && std::fabs(p.y) <= kMaxCoordinate &&
         std::fabs(p.z) <= kMaxCoordinate;
}

// `what` names the point in the message, e.g. "the camera position".
void check_coordinates(Vec3 p, const JsonValue& where, const std::string& what) {
  if (!within_coordinate_bound(p)) {
    where.fail(what + " " + describe_point(p) + " is beyond the coordinate bound; " +
               coordinate_bound_expectation());
  }
}

// `mesh` is in world space; `what` names it in the message, e.g. "the quad".
void check_mesh_coordinates(const TriangleMesh& mesh, const JsonValue& where,
                            const std::string& what) {
  const auto outside = std::find_if(mesh.positions.begin(), mesh.positions.end(),
                                    [](Vec3 p) { return !within_coordinate_bound(p); });
  if (outside == mesh.positions.end()) return;
  check_coordinates(*outside, where,
                    "vertex " + std::to_string(outside - mesh.positions.begin()) + " of " + what +
                        ", after the transform at");
}

// The three columns of the linear part.
// A point of the scene read from `value`, within the coordinate bound; `what` names it.
Vec3 read_point(const JsonValue& value, const std::string& what) {
  const Vec3 p = value.vec3();
  check_coordinates(p, value, what);
  return p;
}

// The unit direction from `origin` (named by origin_name) to the target read from
// target_value. Closer than about 1e-19 the squared distance underflows in float and leaves no
// direction; `purpose` says what the direction is for.
Vec3 direction_to_target(Vec3 origin, Vec3 target, const JsonValue& target_value,
                         const std::string& origin_name, const std::string& purpose) {
  const Vec3 axis = normalize(target - origin);
  if (!(std::fabs(length(axis) - 1) < 1e-5f)) {
    target_value.expected("a point different from " + origin_name +
                          ", far enough from it (about 1e-19) to give " + purpose +
                          " in single precision");
  }
  return axis;
}

Vec3 column(const Transform& t, int j) {
  return {t.m[0][j], t.m[1][j], t.m[2][j]};
}

bool is_similarity(const Transform& t) {
  const float s2 = dot(column(t, 0), column(t, 0));
  const float tolerance = 1e-4f * s2;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const float expected = i == j ? s2 : 0.0f;
      if (std::fabs(dot(column(t, i), column(t, j)) - expected) > tolerance) return false;
    }
  }
  return true;
}

bool is_rotation(const Transform& t) {
  return is_similarity(t) && std::fabs(dot(column(t, 0), column(t, 0)) - 1) < 1e-4f &&
         t.determinant() > 0 && t.m[0][3] == 0 && t.m[1][3] == 0 && t.m[2][3] == 0;
}

// An environment light's radiance is its scale times the image's pixels.
void check_scaled_image(const RgbImage& image, Rgb scale, const JsonValue& where) {
  Rgb brightest(0.0f);
  for (const Rgb& pixel : image.pixels) brightest = vmax(brightest, pixel);
  const Rgb product = scale * brightest;
  if (!is_finite(product) || max_component(product) > kMaxBrightness) {
    where.expected("a scale whose product with the image's brightest pixel " +
                   describe_point(brightest) + " is at most 1e30 (kMaxBrightness)");
  }
}

// Transforms are lists of operations applied in order, first to last:
//   {"translate": [x, y, z]}, {"rotate": {"axis": [x, y, z], "degrees": d}},
//   {"scale": s or [sx, sy, sz]}, {"matrix": 3 or 4 rows of 4 numbers}.
Transform parse_transform(const JsonValue& value) {
  Transform result;
  for (const JsonValue& op_value : value.array()) {
    const JsonObject op = op_value.object({"translate", "rotate", "scale", "matrix"});
    if (op.value().json().size() != 1) {
      op_value.expected("an object with exactly one of: translate, rotate, scale, matrix");
    }
    Transform step;
    if (auto t = op.optional("translate")) {
      step = Transform::translate(t->vec3());
    } else if (auto r = op.optional("rotate")) {
      const JsonObject rotate = r->object({"axis", "degrees"});
      const Vec3 axis = rotate.required("axis").direction().unit;
      step = Transform::rotate(axis, degrees_to_radians(rotate.required("degrees").real()));
    } else if (auto s = op.optional("scale")) {
      step = Transform::scale(s->rgb({0.0, std::numeric_limits<double>::infinity(), true}));
    } else {
      const JsonValue m = op.required("matrix");
      if (!m.json().is_array() || (m.json().size() != 3 && m.json().size() != 4)) {
        m.expected("3 or 4 rows of 4 numbers");
      }
      const std::vector<JsonValue> rows = m.array();
      for (int i = 0; i < static_cast<int>(rows.size()); ++i) {
        const std::vector<JsonValue> row = rows[i].array(4);
        for (int j = 0; j < 4; ++j) {
          const float x = row[j].real();
          if (i < 3) {
            step.m[i][j] = x;
          } else if (x != (j == 3 ? 1.0f : 0.0f)) {
            row[j].expected(j == 3 ? "1 (the last row must be [0, 0, 0, 1])"
                                   : "0 (the last row must be [0, 0, 0, 1])");
          }
        }
      }
    }
    result = step * result;
  }
  for (const auto& row : result.m) {
    if (!std::all_of(std::begin(row), std::end(row), [](float x) { return std::isfinite(x); })) {
      value.fail("the combined transform has entries beyond single-precision range");
    }
  }
  if (!(std::fabs(result.determinant()) > 0)) value.fail("the transform is not invertible");
  return result;
}

class SceneReader {
 public:
  SceneReader(std::string origin, std::string base_dir, const MemoryBudget& budget)
      : origin_(std::move(origin)), base_dir_(std::move(base_dir)), budget_(budget) {}

  LoadedScene read(const json& doc) {
    const JsonValue root(doc, "", origin_);
    const JsonObject top = root.object(
        {"name", "camera", "render", "materials", "media", "shapes", "lights", "include"});
    Scene& scene = out_.scene;
    scene.name =
        top.has("name") ? top.required("name").string() : fs::path(origin_).stem().string();
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

 private:
  // Absolute path of a mesh or image, and how the canonical document names it.
  struct ResolvedPath {
    std::string file;
    std::string canonical;
  };

  ResolvedPath resolve(const std::string& name) const {
    const fs::path p(name);
    if (p.is_absolute()) return {p.lexically_normal().string(), p.lexically_normal().string()};
    if (name.starts_with(kDataPrefix)) {
      return {
          (fs::path(SNEE_DATA_DIR) / name.substr(kDataPrefix.size())).lexically_normal().string(),
          p.lexically_normal().string()};
    }
    const std::string file = fs::absolute(fs::path(base_dir_) / p).lexically_normal().string();
    return {file, file};
  }

  void read_camera(const JsonValue& value) {
    const JsonObject obj = value.object({"type", "position", "look_at", "up", "fov", "fov_axis",
                                         "aperture_radius", "focus_distance", "resolution"});
    if (auto type = obj.optional("type")) type->choice({"pinhole"});
    Camera& camera = out_.scene.camera;
    camera.position = read_point(obj.required("position"), "the camera position");
    const JsonValue look_at = obj.required("look_at");
    camera.look_at = read_point(look_at, "the look_at point");
    // The renderer builds the camera's frame from normalize(look_at - position) in float.
    const Vec3 view = direction_to_target(camera.position, camera.look_at, look_at,
                                          "the camera position", "a viewing direction");
    Vec3 up_as_given = camera.up;
    if (auto up = obj.optional("up")) {
      const Direction up_direction = up->direction();
      up_as_given = up_direction.given;
      camera.up = up_direction.unit;
      if (!(length(cross(view, camera.up)) > 1e-4f)) {
        up->expected("a direction not parallel to the viewing direction");
      }
    }
    if (auto axis = obj.optional("fov_axis")) {
      const std::string name = axis->choice({"vertical", "horizontal", "diagonal"});
      camera.fov_axis = name == "horizontal" ? FovAxis::kHorizontal
                        : name == "diagonal" ? FovAxis::kDiagonal
                                             : FovAxis::kVertical;
    }
    if (auto fov = obj.optional("fov")) read_fov(*fov, camera);
    if (auto focus = obj.optional("focus_distance")) camera.focus_distance = focus->real(kPositive);
    if (auto aperture = obj.optional("aperture_radius")) read_aperture(*aperture, camera);
    if (auto resolution = obj.optional("resolution")) {
      const std::vector<JsonValue> wh = resolution->array(2);
      camera.width = static_cast<int>(wh[0].integer(1, kMaxImageEdge));
      camera.height = static_cast<int>(wh[1].integer(1, kMaxImageEdge));
    }
    canonical_["camera"] = canonical_camera(camera, up_as_given);
  }

  static void read_fov(const JsonValue& fov, Camera& camera) {
    camera.fov_degrees = fov.real({0.0, 180.0, true, true});
    // The image plane's half extent, as the renderer computes it in float; for a subnormal
    // fov it rounds to 0 and every pixel would see along the same ray.
    if (!(tan_half_angle(camera.fov_degrees) > 0)) {
      fov.expected(
          "a number in (0, 180) whose half-angle tangent is positive in single "
          "precision");
    }
    // Along the horizontal or the diagonal the height follows from the aspect ratio, which
    // --resolution may take to kMaxImageEdge : 1.
    Camera widest = camera;
    widest.width = kMaxImageEdge;
    widest.height = 1;
    if (camera.fov_axis != FovAxis::kVertical && !(image_half_extents(widest).y > 0)) {
      fov.expected(
          "a number in (0, 180) whose half-angle tangent, divided by the widest aspect ratio " +
          std::to_string(kMaxImageEdge) + ", is positive in single precision");
    }
  }

  // After the focus distance: the ratio of the two sets the rays' spread.
  static void read_aperture(const JsonValue& aperture, Camera& camera) {
    const float a = aperture.real(kNonNegative);
    camera.aperture_radius = a;
    const Vec3 p = camera.position;
    if (!within_coordinate_bound({std::fabs(p.x) + a, std::fabs(p.y) + a, std::fabs(p.z) + a})) {
      aperture.expected("a radius that keeps the lens around the camera position within +-" +
                        describe_number(kMaxCoordinate));
    }
    // Directions leave the lens along (film offset) - (lens point) / focus distance; the bound
    // keeps their squared length far inside float.
    if (!(a <= kMaxApertureOverFocus * effective_focus_distance(camera))) {
      aperture.expected("a radius at most " + describe_number(kMaxApertureOverFocus) +
                        " times the focus distance (" +
                        describe_number(effective_focus_distance(camera)) + ")");
    }
  }

  // Keys beyond the pinhole's only where they differ from their defaults, so that the document,
  // and with it the scene hash, of a scene without them stays what it was.
  static json canonical_camera(const Camera& camera, Vec3 up_as_given) {
    json c = {{"type", "pinhole"},
              {"position", to_json(camera.position)},
              {"look_at", to_json(camera.look_at)},
              {"up", to_json(up_as_given)},
              {"fov", camera.fov_degrees},
              {"resolution", json::array({camera.width, camera.height})}};
    if (camera.fov_axis == FovAxis::kHorizontal) c["fov_axis"] = "horizontal";
    if (camera.fov_axis == FovAxis::kDiagonal) c["fov_axis"] = "diagonal";
    if (camera.aperture_radius > 0) c["aperture_radius"] = camera.aperture_radius;
    if (camera.focus_distance > 0) c["focus_distance"] = camera.focus_distance;
    return c;
  }

  // A glTF asset placed in the scene: {"file", "transform", "resolution", "materials",
  // "media", "shading"}; "shading" applies to every primitive, as for a mesh shape. "materials" and
  // "media" map a glTF material's name to a snee material or medium (a defined name or an inline
  // definition; a medium may be null for none) that replaces what the asset's material gives.
  // Returns the asset's camera, with "resolution" applied.
  std::optional<Camera> read_include(const JsonValue& value) {
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
      camera->width = std::clamp(
          static_cast<int>(std::lround(camera->height * asset.camera_aspect)), 1, kMaxImageEdge);
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

  void read_render(const JsonValue& value) {
    const JsonObject obj =
        value.object({"spp", "max_depth", "seed", "integrator", "noise_target", "light_selection"});
    RenderSettings& render = out_.scene.render;
    if (auto spp = obj.optional("spp")) render.spp = static_cast<int>(spp->integer(1, INT32_MAX));
    if (auto depth = obj.optional("max_depth")) {
      render.max_depth = static_cast<int>(depth->integer(0, INT32_MAX));
    }
    if (auto seed = obj.optional("seed")) {
      render.seed = static_cast<uint32_t>(seed->integer(0, UINT32_MAX));
    }
    if (auto integrator = obj.optional("integrator")) render.integrator = integrator->string();
    if (auto target = obj.optional("noise_target"))
      render.noise_target = target->number(kNonNegative);
    if (auto selection = obj.optional("light_selection")) {
      const auto parsed =
          selection->json().is_string() ? parse_light_selection(selection->string()) : std::nullopt;
      if (!parsed) selection->expected("one of: uniform, power");
      render.light_selection = *parsed;
    }
  }

  json canonical_render() const {
    const RenderSettings& render = out_.scene.render;
    json canonical = {{"spp", render.spp},
                      {"max_depth", render.max_depth},
                      {"seed", render.seed},
                      {"integrator", render.integrator}};
    // Written only when set, so the scene hash of a scene without one stays what it was.
    if (render.noise_target > 0) canonical["noise_target"] = render.noise_target;
    if (render.light_selection != LightSelection::kUniform) {
      canonical["light_selection"] = light_selection_name(render.light_selection);
    }
    return canonical;
  }

  // Definitions in the top-level lists must be named; one written inline in a shape may be, and
  // is otherwise named by the JSON path it sits at, which no sensible name collides with.
  std::string unique_name(const JsonObject& obj, bool top_level,
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

  // A mesh whose material has a texture needs texture coordinates to look it up with (a sphere
  // has its own, surface_uv.h); `what` names the shape in the error at `where`.
  void require_texture_coordinates(const Shape& shape, const JsonValue& where,
                                   const std::string& what, const std::string& detail) const {
    const Material& material = out_.scene.materials[static_cast<size_t>(shape.material)];
    if (!material.has_texture() || shape.kind == ShapeKind::kSphere || !shape.mesh.uvs.empty()) {
      return;
    }
    where.fail("the material '" + material.name + "' has a texture, but the " + what +
               " has no texture coordinates" + detail);
  }

  // The texture read from `file`, read once however many materials use it as the same kind of
  // values; `where` is the JSON value naming it.
  int add_texture(const JsonValue& where, const std::string& file,
                  PixelValues values = PixelValues::kColour) {
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

  // A dielectric's or conductor's `roughness` and `roughness_texture`. With a texture,
  // roughness is a factor on it (as glTF's roughnessFactor is), 1 by default.
  void add_roughness(const JsonObject& obj, Material& material, json& canonical) {
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

  int add_material(const JsonValue& value, bool top_level) {
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
      const JsonObject obj =
          value.object({"name", "type", "ior", "roughness", "roughness_texture"});
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

  // A conductor's "metal" (a named index) or its "eta" and "k".
  static ComplexIor conductor_ior(const JsonObject& obj) {
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

  // A grid medium's density: {"file": a .vol file} or {"resolution": [nx, ny, nz], "values":
  // [...]}, with "bounds": {"min": [x, y, z], "max": [x, y, z]} placing the grid in the world
  // (required for inline values; a file's own box otherwise).
  // `canonical` receives the density as the canonical scene writes it.
  DensityGrid density_grid(const JsonValue& value, json& canonical) {
    const JsonObject obj = value.object({"file", "resolution", "values", "bounds"});
    if (obj.has("file") == obj.has("values")) {
      value.fail("expected either file (a .vol density grid) or resolution and values");
    }
    DensityGrid grid;
    if (auto file_name = obj.optional("file")) {
      if (obj.has("resolution")) {
        obj.required("resolution").fail("a file gives its own resolution; expected none here");
      }
      const ResolvedPath file = resolve(file_name->string());
      try {
        grid = read_density_grid(file.file, budget_);
      } catch (const SceneError& e) {
        file_name->fail(e.what());
      }
      grid.source = file.file;
      canonical["file"] = file.canonical;
    } else {
      const std::vector<JsonValue> resolution = obj.required("resolution").array(3);
      const auto axis = [](const JsonValue& n) { return static_cast<int>(n.integer(1, 1 << 16)); };
      grid.nx = axis(resolution[0]);
      grid.ny = axis(resolution[1]);
      grid.nz = axis(resolution[2]);
      const JsonValue values = obj.required("values");
      const uint64_t voxels = static_cast<uint64_t>(grid.nx) * static_cast<uint64_t>(grid.ny) *
                              static_cast<uint64_t>(grid.nz);
      if (!values.json().is_array() || values.json().size() != voxels) {
        values.expected("an array of " + std::to_string(voxels) + " densities (one per voxel, x " +
                        "fastest, then y, then z)");
      }
      for (const JsonValue& v : values.array()) grid.values.push_back(v.real(kNonNegative));
      if (!obj.has("bounds")) value.fail("inline values need bounds (min and max) to place them");
      grid.source = value.path();
      canonical["resolution"] = {grid.nx, grid.ny, grid.nz};
      canonical["values"] = grid.values;
    }
    if (auto bounds = obj.optional("bounds")) {
      const JsonObject box = bounds->object({"min", "max"});
      grid.lo = box.required("min").vec3();
      grid.hi = box.required("max").vec3();
    }
    try {
      validate_density_grid(grid, grid.source);
    } catch (const SceneError& e) {
      value.fail(e.what());
    }
    canonical["bounds"] = {{"min", to_json(grid.lo)}, {"max", to_json(grid.hi)}};
    return grid;
  }

  // A medium's albedo from the image that `where` names: its mean colour, one albedo for the
  // whole medium (the medium stays homogeneous, as SNEE's samplers require).
  Rgb mean_albedo(const JsonValue& where) {
    const ResolvedPath file = resolve(where.string());
    RgbImage image;
    try {
      image = read_rgb_image(file.file, "medium albedo texture", budget_);
    } catch (const SceneError& e) {
      where.fail(e.what());
    }
    double sum[3] = {0, 0, 0};
    for (const Rgb& c : image.pixels) {
      for (int i = 0; i < 3; ++i) sum[i] += c[i];
    }
    const double n = static_cast<double>(image.pixels.size());
    if (!(n > 0)) where.fail(file.file + ": the image has no pixels");
    const Rgb mean(static_cast<float>(sum[0] / n), static_cast<float>(sum[1] / n),
                   static_cast<float>(sum[2] / n));
    if (mean.x > 1 || mean.y > 1 || mean.z > 1) {
      where.fail(file.file + ": the mean colour " + describe_point(mean) +
                 " is above 1; an albedo is at most 1 in each channel");
    }
    return mean;
  }

  int add_medium(const JsonValue& value, bool top_level) {
    const JsonObject obj = value.object({"name", "type", "sigma_s", "sigma_a", "albedo",
                                         "albedo_texture", "mean_free_path", "g", "density"});
    const std::string type = obj.has("type") ? obj.required("type").choice({"homogeneous", "grid"})
                                             : std::string("homogeneous");
    Medium medium;
    json canonical_grid;
    if (type == "grid") {
      medium.density = std::make_shared<const DensityGrid>(
          density_grid(obj.required("density"), canonical_grid));
    } else if (auto density = obj.optional("density")) {
      density->fail("a density belongs to a medium of type \"grid\"; expected no density here");
    }
    medium.name = unique_name(obj, top_level, medium_names_, "medium");
    const bool by_coefficients = obj.has("sigma_s") || obj.has("sigma_a");
    const bool by_albedo =
        obj.has("albedo") || obj.has("albedo_texture") || obj.has("mean_free_path");
    if (by_coefficients == by_albedo) {
      value.fail(
          "expected either sigma_s (and optionally sigma_a) or albedo (or albedo_texture) and "
          "mean_free_path");
    }
    if (by_coefficients) {
      medium.sigma_s = obj.required("sigma_s").rgb(kNonNegative);
      if (auto sigma_a = obj.optional("sigma_a")) medium.sigma_a = sigma_a->rgb(kNonNegative);
      if (!is_finite(medium.sigma_t())) {
        value.fail("sigma_s + sigma_a " + describe_point(medium.sigma_t()) +
                   " is beyond single-precision range; expected a smaller sum");
      }
    } else {
      const std::optional<JsonValue> texture = obj.optional("albedo_texture");
      Rgb albedo = texture ? Rgb(1.0f) : obj.required("albedo").rgb(kUnitInterval);
      if (texture) {
        if (auto factor = obj.optional("albedo")) albedo = factor->rgb(kUnitInterval);
        albedo = albedo * mean_albedo(*texture);
      }
      const JsonValue mean_free_path = obj.required("mean_free_path");
      const Rgb sigma_t = Rgb(1.0f) / mean_free_path.rgb(kPositive);
      // Below about 3e-39, sigma_t = 1 / mean_free_path overflows and albedo 0 times it is NaN.
      if (!is_finite(sigma_t)) {
        mean_free_path.expected(
            "mean free paths whose inverse (sigma_t) is finite in single precision, i.e. at "
            "least 3e-39");
      }
      medium.sigma_s = albedo * sigma_t;
      medium.sigma_a = (Rgb(1.0f) - albedo) * sigma_t;
    }
    if (auto g = obj.optional("g")) medium.g = g->real({-1.0, 1.0, true, true});
    nlohmann::json canonical = {{"name", medium.name},
                                {"type", type},
                                {"sigma_s", to_json(medium.sigma_s)},
                                {"sigma_a", to_json(medium.sigma_a)},
                                {"g", medium.g}};
    if (medium.density) canonical["density"] = std::move(canonical_grid);
    canonical_media_.push_back(std::move(canonical));
    medium_names_[medium.name] = value.path();
    out_.scene.media.push_back(medium);
    return static_cast<int>(out_.scene.media.size() - 1);
  }

  // A shape's material or medium: the name of a defined one, or an inline definition.
  int reference(const JsonValue& value, bool is_material) {
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

  // "shading" of a mesh: "smooth" (interpolated vertex normals; the default where the mesh has
  // them) or "flat". Recorded in the canonical form only for meshes with normals, where it
  // makes a difference.
  bool read_shading(const std::optional<JsonValue>& shading, const TriangleMesh& mesh,
                    const std::string& source, json& canonical) const {
    const bool has_normals = !mesh.normals.empty();
    bool smooth = has_normals;
    if (shading) {
      smooth = shading->choice({"smooth", "flat"}) == "smooth";
      if (smooth && !has_normals) {
        shading->fail("\"smooth\" needs vertex normals, and " + source +
                      " has none (expected \"flat\", or a mesh file with normals)");
      }
    }
    if (has_normals) canonical["shading"] = smooth ? "smooth" : "flat";
    return smooth;
  }

  void read_shape(const JsonValue& value) {
    const std::string type = value.member("type").choice({"mesh", "sphere", "quad"});
    const std::initializer_list<std::string_view> mesh_keys = {"name",     "type",      "transform",
                                                               "material", "medium",    "emission",
                                                               "file",     "normalize", "shading"};
    const std::initializer_list<std::string_view> sphere_keys = {
        "name", "type", "transform", "material", "medium", "emission", "center", "radius"};
    const std::initializer_list<std::string_view> quad_keys = {
        "name", "type", "transform", "material", "medium", "emission", "size"};
    const JsonObject obj = value.object(type == "mesh"     ? mesh_keys
                                        : type == "sphere" ? sphere_keys
                                                           : quad_keys);

    Shape shape;
    EdgeCounts edges;
    json canonical = {{"type", type}};
    const std::optional<JsonValue> transform_value = obj.optional("transform");
    const Transform transform = transform_value ? parse_transform(*transform_value) : Transform();
    shape.source = origin_ + ": " + value.path();

    if (type == "mesh") {
      const JsonValue file_value = obj.required("file");
      const ResolvedPath file = resolve(file_value.string());
      try {
        shape.mesh = load_mesh(file.file, budget_);
      } catch (const SceneError& e) {
        file_value.fail(e.what());
      }
      shape.source = file.file;
      shape.name = fs::path(file.file).stem().string();
      const bool normalize = obj.has("normalize") && obj.required("normalize").boolean();
      Transform placement = transform;
      if (normalize) placement = transform * normalizing_transform(shape.mesh);
      apply_transform(placement, shape.mesh);
      check_mesh_coordinates(shape.mesh, value, shape.source);
      canonical["file"] = file.canonical;
      canonical["normalize"] = normalize;
      shape.smooth_shading =
          read_shading(obj.optional("shading"), shape.mesh, shape.source, canonical);
    } else if (type == "sphere") {
      if (transform_value && !is_similarity(transform)) {
        transform_value->fail(
            "expected a similarity transform for a sphere (rotations, uniform scales, "
            "translations)");
      }
      const Vec3 center = obj.has("center") ? obj.required("center").vec3() : Vec3(0.0f);
      const float radius = obj.has("radius") ? obj.required("radius").real(kPositive) : 1.0f;
      shape.kind = ShapeKind::kSphere;
      shape.center = transform.point(center);
      shape.radius = radius * transform.uniform_scale();
      if (!within_coordinate_bound(shape.center - Vec3(shape.radius)) ||
          !within_coordinate_bound(shape.center + Vec3(shape.radius))) {
        value.fail("the sphere, after the transform at centre " + describe_point(shape.center) +
                   " with radius " + describe_number(shape.radius) +
                   ", reaches beyond the coordinate bound; " + coordinate_bound_expectation());
      }
      shape.name = "sphere";
      canonical["center"] = to_json(center);
      canonical["radius"] = radius;
    } else {
      float width = 1, depth = 1;
      if (auto size = obj.optional("size")) {
        if (size->json().is_number()) {
          width = depth = size->real(kPositive);
        } else {
          const std::vector<JsonValue> wd = size->array(2);
          width = wd[0].real(kPositive);
          depth = wd[1].real(kPositive);
        }
      }
      // Counter-clockwise seen from +y, so the front side faces +y before the transform.
      const float hw = 0.5f * width, hd = 0.5f * depth;
      shape.mesh.positions = {{-hw, 0, -hd}, {-hw, 0, hd}, {hw, 0, hd}, {hw, 0, -hd}};
      shape.mesh.indices = {0, 1, 2, 0, 2, 3};
      // Seen from the front with -z up the image, as a texture lies on the quad.
      shape.mesh.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
      apply_transform(transform, shape.mesh);
      check_mesh_coordinates(shape.mesh, value, "the quad");
      shape.name = "quad";
      canonical["size"] = json::array({width, depth});
    }
    if (auto name = obj.optional("name")) shape.name = name->string();

    if (shape.kind == ShapeKind::kMesh) {
      // A mirroring transform turns the winding inside out; undo that so the front side stays
      // the authored one, then make closed meshes face outward whatever the file said.
      if (transform.determinant() < 0) flip_winding(shape.mesh);
      // Vertices split where their normals differ (mesh_io.cpp) still join their triangles.
      edges = shape.mesh.normals.empty() ? count_edges(shape.mesh)
                                         : count_edges(welded_by_position(shape.mesh));
      shape.closed = edges.boundary == 0;
      if (shape.closed && signed_volume(shape.mesh) < 0) flip_winding(shape.mesh);
    }

    shape.material = reference(obj.required("material"), true);
    canonical["material"] = out_.scene.materials[shape.material].name;
    require_texture_coordinates(shape, obj.required("material"), "mesh '" + shape.source + "'",
                                " to look it up with");
    if (auto medium = obj.optional("medium")) {
      shape.interior_medium = reference(*medium, false);
      canonical["medium"] = out_.scene.media[shape.interior_medium].name;
      if (!bounds_media(out_.scene.materials[shape.material].kind)) {
        medium->fail(
            "an interior medium needs a dielectric or null material (light cannot "
            "enter through a diffuse, diffuse_transmission or conductor surface)");
      }
      if (!shape.closed) {
        out_.warnings.push_back(origin_ + ": " + value.path() + ": the mesh '" + shape.source +
                                "' has an interior medium but is open (" +
                                std::to_string(edges.boundary) +
                                " boundary edges); paths inside may leak out through the holes");
      }
    }
    if (auto emission = obj.optional("emission")) shape.emission = emission->rgb(kBrightness);
    canonical["emission"] = to_json(shape.emission);
    canonical["name"] = shape.name;
    canonical["transform"] = to_json(transform);
    canonical_shapes_.push_back(canonical);
    shape_places_.push_back(origin_ + ": " + value.path());
    out_.scene.shapes.push_back(std::move(shape));
  }

  // A path carries one medium at a time (docs/scene-format.md, "Several media").
  void check_volumes() {
    const Scene& scene = out_.scene;
    const auto describe = [&](int shape) {
      return shape_places_[shape] + " ('" + scene.shapes[shape].name + "')";
    };
    for (const VolumeContact& c : find_volume_contacts(scene)) {
      const std::string relation = c.inside ? " lies inside " : " overlaps ";
      if (is_volume(scene, c.other)) {
        throw SceneError(describe(c.other) + relation + describe(c.volume) +
                         ": both are volumes (a dielectric boundary or an interior medium), and "
                         "a path carries one medium at a time, so the shared part would render "
                         "with the wrong one; move them apart (see \"Several media\" in "
                         "docs/scene-format.md)");
      }
      out_.warnings.push_back(
          describe(c.other) +
          (c.inside ? " lies inside the volume " : " reaches into the volume ") +
          describe(c.volume) +
          ": where it is inside, its shadow rays carry no medium and SNEE "
          "may take it for the boundary, so its lighting there is not exact");
    }
  }

  Transform read_rotation(const JsonValue& value) {
    const Transform rotation = parse_transform(value);
    if (!is_rotation(rotation)) value.fail("expected a rotation (no scale, mirror or translation)");
    return rotation;
  }

  void read_light(const JsonValue& value) {
    const std::string type = value.member("type").choice(
        {"directional", "cone", "constant", "envmap", "sky", "point", "spot"});
    Light light;
    json canonical = {{"type", type}};
    if (type == "directional") {
      const JsonObject obj = value.object({"type", "direction", "irradiance"});
      light.kind = LightKind::kDirectional;
      const Direction direction = obj.required("direction").direction();
      light.direction = direction.unit;
      if (auto e = obj.optional("irradiance")) light.irradiance = e->rgb(kBrightness);
      canonical["direction"] = to_json(direction.given);
      canonical["irradiance"] = to_json(light.irradiance);
    } else if (type == "cone") {
      const JsonObject obj = value.object({"type", "direction", "half_angle_degrees", "radiance"});
      light.kind = LightKind::kCone;
      const Direction direction = obj.required("direction").direction();
      light.direction = direction.unit;
      const JsonValue half_angle_value = obj.required("half_angle_degrees");
      const float half_angle_degrees = half_angle_value.real({0.0, 180.0, true, false});
      light.half_angle = degrees_to_radians(half_angle_degrees);
      // The cone's solid angle is 2 pi (1 - cos(half angle)), in float: below about 0.014
      // degrees the cosine rounds to 1 and the light could neither be hit nor sampled.
      if (!(std::cos(light.half_angle) < 1.0f)) {
        half_angle_value.expected(
            "an angle in (0, 180] whose cosine is below 1 in single precision (at least about "
            "0.014 degrees)");
      }
      if (auto l = obj.optional("radiance")) light.radiance = l->rgb(kBrightness);
      canonical["direction"] = to_json(direction.given);
      canonical["half_angle_degrees"] = half_angle_degrees;
      canonical["radiance"] = to_json(light.radiance);
    } else if (type == "constant") {
      const JsonObject obj = value.object({"type", "radiance"});
      light.kind = LightKind::kConstantEnv;
      if (auto l = obj.optional("radiance")) light.radiance = l->rgb(kBrightness);
      canonical["radiance"] = to_json(light.radiance);
    } else if (type == "envmap" || type == "sky") {
      const JsonObject obj = type == "envmap" ? value.object({"type", "file", "scale", "rotation"})
                                              : value.object({"type", "scale", "rotation"});
      light.kind = LightKind::kEnvMap;
      if (type == "envmap") {
        const JsonValue file_value = obj.required("file");
        const ResolvedPath file = resolve(file_value.string());
        try {
          out_.scene.env_images.push_back(read_env_image(file.file, budget_));
        } catch (const SceneError& e) {
          file_value.fail(e.what());
        }
        canonical["file"] = file.canonical;
      } else {
        out_.scene.env_images.push_back(make_soft_sky(kSkyWidth, kSkyHeight));
      }
      light.env_image = static_cast<int>(out_.scene.env_images.size() - 1);
      const std::optional<JsonValue> scale = obj.optional("scale");
      if (scale) light.radiance = scale->rgb(kBrightness);
      check_scaled_image(out_.scene.env_images.back(), light.radiance, scale ? *scale : value);
      if (auto rotation = obj.optional("rotation")) light.env_rotation = read_rotation(*rotation);
      canonical["scale"] = to_json(light.radiance);
      canonical["rotation"] = to_json(light.env_rotation);
    } else if (type == "spot") {
      read_spot(value, light, canonical);
    } else {
      const JsonObject obj = value.object({"type", "position", "intensity"});
      light.kind = LightKind::kPoint;
      light.position = read_point(obj.required("position"), "the light position");
      if (auto i = obj.optional("intensity")) light.intensity = i->rgb(kBrightness);
      canonical["position"] = to_json(light.position);
      canonical["intensity"] = to_json(light.intensity);
    }
    canonical_lights_.push_back(canonical);
    out_.scene.lights.push_back(light);
  }

  void read_spot(const JsonValue& value, Light& light, json& canonical) {
    const JsonObject obj = value.object({"type", "position", "look_at", "intensity",
                                         "cone_angle_degrees", "falloff_start_degrees"});
    light.kind = LightKind::kSpot;
    light.position = read_point(obj.required("position"), "the light position");
    const JsonValue look_at_value = obj.required("look_at");
    const Vec3 look_at = read_point(look_at_value, "the look_at point");
    light.spot_axis = direction_to_target(light.position, look_at, look_at_value,
                                          "the light position", "an axis");
    if (auto i = obj.optional("intensity")) light.intensity = i->rgb(kBrightness);
    float cone_degrees = 30.0f;
    if (auto cone = obj.optional("cone_angle_degrees")) {
      cone_degrees = cone->real({0.0, 180.0, true, false});
    }
    // pbrt's default: the falloff spans the cone's last 5 degrees.
    float falloff_degrees = std::max(0.0f, cone_degrees - 5.0f);
    if (auto falloff = obj.optional("falloff_start_degrees")) {
      falloff_degrees = falloff->real({0.0, cone_degrees});
    }
    light.spot_cos_outer = std::cos(degrees_to_radians(cone_degrees));
    light.spot_cos_inner = std::cos(degrees_to_radians(falloff_degrees));
    canonical["position"] = to_json(light.position);
    canonical["look_at"] = to_json(look_at);
    canonical["intensity"] = to_json(light.intensity);
    canonical["cone_angle_degrees"] = cone_degrees;
    canonical["falloff_start_degrees"] = falloff_degrees;
  }

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

}  // namespace

LoadedScene load_scene_json(const json& doc, const std::string& origin, const std::string& base_dir,
                            const MemoryBudget& budget) {
  return SceneReader(origin, base_dir, budget).read(doc);
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
