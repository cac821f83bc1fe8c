#include "scene/scene_json_values.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <sstream>
#include <vector>

namespace snee {

using nlohmann::json;

json to_json(Vec3 v) {
  return json::array({v.x, v.y, v.z});
}

json to_json(const Transform& t) {
  json rows = json::array();
  for (const auto& row : t.m) rows.push_back(json::array({row[0], row[1], row[2], row[3]}));
  return json::array({json{{"matrix", rows}}});
}

float degrees_to_radians(float degrees) {
  return degrees * (kPi / 180.0f);
}

std::string describe_number(float x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

std::string describe_point(Vec3 p) {
  // Streamed rather than concatenated: GCC 12 reports a false -Wrestrict on "(" + string
  // once the concatenation is inlined (GCC bug 105329).
  std::ostringstream s;
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

std::string coordinate_bound_expectation() {
  return "expected every world-space coordinate within +-" + describe_number(kMaxCoordinate);
}

bool within_coordinate_bound(Vec3 p) {
  return std::fabs(p.x) <= kMaxCoordinate && std::fabs(p.y) <= kMaxCoordinate &&
         std::fabs(p.z) <= kMaxCoordinate;
}

void check_coordinates(Vec3 p, const JsonValue& where, const std::string& what) {
  if (!within_coordinate_bound(p)) {
    where.fail(what + " " + describe_point(p) + " is beyond the coordinate bound; " +
               coordinate_bound_expectation());
  }
}

void check_mesh_coordinates(const TriangleMesh& mesh, const JsonValue& where,
                            const std::string& what) {
  const auto outside = std::find_if(mesh.positions.begin(), mesh.positions.end(),
                                    [](Vec3 p) { return !within_coordinate_bound(p); });
  if (outside == mesh.positions.end()) return;
  check_coordinates(*outside, where,
                    "vertex " + std::to_string(outside - mesh.positions.begin()) + " of " + what +
                        ", after the transform at");
}

Vec3 read_point(const JsonValue& value, const std::string& what) {
  const Vec3 p = value.vec3();
  check_coordinates(p, value, what);
  return p;
}

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

namespace {

// The three columns of the linear part.
Vec3 column(const Transform& t, int j) {
  return {t.m[0][j], t.m[1][j], t.m[2][j]};
}

}  // namespace

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

void check_scaled_image(const RgbImage& image, Rgb scale, const JsonValue& where) {
  Rgb brightest(0.0f);
  for (const Rgb& pixel : image.pixels) brightest = vmax(brightest, pixel);
  const Rgb product = scale * brightest;
  if (!is_finite(product) || max_component(product) > kMaxBrightness) {
    where.expected("a scale whose product with the image's brightest pixel " +
                   describe_point(brightest) + " is at most 1e30 (kMaxBrightness)");
  }
}

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

}  // namespace snee
