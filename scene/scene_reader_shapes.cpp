// The scene document's shapes (spheres, quads, meshes), their shading, and the check that
// the volumes they enclose do not overlap.
#include <filesystem>
#include <optional>
#include <utility>

#include "scene/mesh_io.h"
#include "scene/mesh_topology.h"
#include "scene/scene_reader.h"
#include "scene/volume_overlap.h"

namespace snee::scene_reader {

namespace fs = std::filesystem;
using nlohmann::json;

bool SceneReader::read_shading(const std::optional<JsonValue>& shading, const TriangleMesh& mesh,
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

void SceneReader::read_shape(const JsonValue& value) {
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

void SceneReader::check_volumes() {
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
    out_.warnings.push_back(describe(c.other) +
                            (c.inside ? " lies inside the volume " : " reaches into the volume ") +
                            describe(c.volume) +
                            ": where it is inside, its shadow rays carry no medium and SNEE "
                            "may take it for the boundary, so its lighting there is not exact");
  }
}

}  // namespace snee::scene_reader
