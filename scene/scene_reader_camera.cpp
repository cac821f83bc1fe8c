// The scene document's "camera" and "render" objects, and their canonical forms.
#include <cmath>

#include "scene/camera_frame.h"
#include "scene/scene_reader.h"

namespace snee::scene_reader {

using nlohmann::json;

void SceneReader::read_camera(const JsonValue& value) {
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

void SceneReader::read_fov(const JsonValue& fov, Camera& camera) {
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

void SceneReader::read_aperture(const JsonValue& aperture, Camera& camera) {
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

json SceneReader::canonical_camera(const Camera& camera, Vec3 up_as_given) {
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

void SceneReader::read_render(const JsonValue& value) {
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

json SceneReader::canonical_render() const {
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

}  // namespace snee::scene_reader
