// The values a scene document is made of, read and checked (points within the coordinate bound,
// directions, transforms, scaled images) and written back in canonical form: what the scene
// reader's parts share (scene_reader.h).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/math.h"
#include "scene/json_reader.h"
#include "scene/rgb_image_io.h"
#include "scene/scene.h"

namespace snee {

inline constexpr NumberRange kBrightness{0.0, kMaxBrightness};
// Relative indices of refraction beyond these are not materials; the bounds keep eta^2 and
// 1 / eta^2 of the Fresnel and radiance-scaling terms far from float's limits.
inline constexpr NumberRange kIorRange{1e-3, 1e3};
// A conductor's eta and k; 0 is allowed for both (eta = 0 with any k reflects everything).
inline constexpr NumberRange kConductorIndexRange{0.0, 1e3};
// The widest thin lens relative to its focus distance.
inline constexpr float kMaxApertureOverFocus = 1e6f;

nlohmann::json to_json(Vec3 v);
nlohmann::json to_json(const Transform& t);

float degrees_to_radians(float degrees);
std::string describe_number(float x);
std::string describe_point(Vec3 p);

std::string coordinate_bound_expectation();
// False for NaN too.
bool within_coordinate_bound(Vec3 p);
// `what` names the point in the message, e.g. "the camera position".
void check_coordinates(Vec3 p, const JsonValue& where, const std::string& what);
// `mesh` is in world space; `what` names it in the message, e.g. "the quad".
void check_mesh_coordinates(const TriangleMesh& mesh, const JsonValue& where,
                            const std::string& what);
// A point of the scene read from `value`, within the coordinate bound; `what` names it.
Vec3 read_point(const JsonValue& value, const std::string& what);
// The unit direction from `origin` (named by origin_name) to the target read from
// target_value. Closer than about 1e-19 the squared distance underflows in float and leaves no
// direction; `purpose` says what the direction is for.
Vec3 direction_to_target(Vec3 origin, Vec3 target, const JsonValue& target_value,
                         const std::string& origin_name, const std::string& purpose);

// Whether the linear part only rotates, reflects and scales uniformly.
bool is_similarity(const Transform& t);
// A rotation without translation.
bool is_rotation(const Transform& t);

// An environment light's radiance is its scale times the image's pixels.
void check_scaled_image(const RgbImage& image, Rgb scale, const JsonValue& where);

// Transforms are lists of operations applied in order, first to last:
//   {"translate": [x, y, z]}, {"rotate": {"axis": [x, y, z], "degrees": d}},
//   {"scale": s or [sx, sy, sz]}, {"matrix": 3 or 4 rows of 4 numbers}.
Transform parse_transform(const JsonValue& value);

}  // namespace snee
