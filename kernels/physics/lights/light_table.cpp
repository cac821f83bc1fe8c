#include "kernels/physics/lights/light_table.h"

#include <algorithm>
#include <cmath>

#include "scene/shape_bounds.h"

namespace snee {

namespace {

// Pixels where the filtered radiance is non-zero get at least this fraction of the map's mean
// luminance as sampling weight, so dim but lit directions keep a pdf that float cdfs can still
// resolve.
constexpr float kEnvWeightFloor = 1e-3f;

bool is_escaping(LightKind kind) {
  return kind == LightKind::kCone || kind == LightKind::kConstantEnv || kind == LightKind::kEnvMap;
}

// The lat-long convention of RgbImage (scene.h), in map space.
Vec2 map_direction_to_uv(Vec3 m) {
  return {std::atan2(m.x, -m.z) / (2.0f * kPi) + 0.5f, safe_acos(m.y) * kInvPi};
}

Vec3 uv_to_map_direction(Vec2 uv) {
  const float theta = uv.y * kPi, phi = 2.0f * kPi * (uv.x - 0.5f);
  const float sin_theta = std::sin(theta);
  return {sin_theta * std::sin(phi), std::cos(theta), -sin_theta * std::cos(phi)};
}

// Bilinear interpolation between pixel centres, at ((x + 1/2) / width, (y + 1/2) / height):
// u wraps around (the map is periodic in longitude), v clamps to the first and last rows
// (within half a pixel of a pole the value is the row's own).
Rgb env_bilinear(const RgbImage& image, Vec2 uv) {
  const float fx = uv.x * static_cast<float>(image.width) - 0.5f;
  const float fy = std::clamp(uv.y * static_cast<float>(image.height) - 0.5f, 0.0f,
                              static_cast<float>(image.height - 1));
  const float x_floor = std::floor(fx), y_floor = std::floor(fy);
  const float tx = fx - x_floor, ty = fy - y_floor;
  const auto wrap = [&](int x) { return ((x % image.width) + image.width) % image.width; };
  const int x0 = wrap(static_cast<int>(x_floor)), x1 = wrap(static_cast<int>(x_floor) + 1);
  const int y0 = static_cast<int>(y_floor), y1 = std::min(y0 + 1, image.height - 1);
  const auto at = [&](int x, int y) {
    return image.pixels[static_cast<size_t>(y) * image.width + x];
  };
  const Rgb top = at(x0, y0) * (1.0f - tx) + at(x1, y0) * tx;
  const Rgb bottom = at(x0, y1) * (1.0f - tx) + at(x1, y1) * tx;
  return top * (1.0f - ty) + bottom * ty;
}

// Whether the bilinear lookup can be non-zero somewhere in pixel (x, y): it blends that pixel
// with its neighbours (u wrapping, v clamped).
bool env_pixel_lit(const RgbImage& image, const std::vector<float>& lum, int x, int y) {
  for (int dy = -1; dy <= 1; ++dy) {
    const int yy = std::clamp(y + dy, 0, image.height - 1);
    for (int dx = -1; dx <= 1; ++dx) {
      const int xx = (x + dx + image.width) % image.width;
      if (lum[static_cast<size_t>(yy) * image.width + xx] > 0) return true;
    }
  }
  return false;
}

// env_rotation is a rotation (the loader rejects anything else), so its inverse is the transpose.
Transform inverse_rotation(const Transform& r) {
  Transform t;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) t.m[i][j] = r.m[j][i];
  }
  return t;
}

Distribution2D env_distribution(const RgbImage& image) {
  const size_t count = static_cast<size_t>(image.width) * image.height;
  std::vector<float> lum(count);
  double sum = 0;
  for (size_t i = 0; i < count; ++i) {
    lum[i] = luminance(vmax(image.pixels[i], Rgb(0.0f)));
    sum += lum[i];
  }
  const float floor = kEnvWeightFloor * static_cast<float>(sum / static_cast<double>(count));
  std::vector<float> weights(count);
  for (int y = 0; y < image.height; ++y) {
    // sin(theta) turns the (u,v) density into one proportional to radiance per solid angle.
    const float sin_theta = std::sin((static_cast<float>(y) + 0.5f) * kPi / image.height);
    for (int x = 0; x < image.width; ++x) {
      const size_t i = static_cast<size_t>(y) * image.width + x;
      // A black pixel beside a lit one still receives bilinear radiance: it gets the floor, so
      // that light sampling reaches every direction with radiance.
      weights[i] = env_pixel_lit(image, lum, x, y) ? std::max(lum[i], floor) * sin_theta : 0.0f;
    }
  }
  return Distribution2D(weights, image.width, image.height);
}

Vec3 triangle_vertex(const TriangleMesh& mesh, size_t triangle, int corner) {
  return mesh.positions[mesh.indices[3 * triangle + corner]];
}

// Cosine of the half-angle of the cone from p that just contains the sphere, or 1 when p is not
// outside it. Rounded outward so the sampled cone never misses part of the sphere; directions
// in the sliver beyond the silhouette miss and are rejected.
float visible_cone_cos(const Shape& sphere, Vec3 p) {
  const Vec3 to_center = sphere.center - p;
  const double d2 = dot(to_center, to_center);
  const double r2 = static_cast<double>(sphere.radius) * sphere.radius;
  if (d2 <= r2) return 1.0f;
  const float cos_max = static_cast<float>(std::sqrt(1.0 - r2 / d2));
  return std::nextafter(cos_max, -1.0f);
}

// Half the diagonal of the box around every shape: a sphere about its centre holds the scene.
double scene_radius(const Scene& scene) {
  ShapeBounds bounds;
  for (const Shape& shape : scene.shapes) bounds.add(shape);
  if (bounds.empty()) return 0;
  const Vec3 d = bounds.hi - bounds.lo;
  return 0.5 * std::sqrt(static_cast<double>(d.x) * d.x + static_cast<double>(d.y) * d.y +
                         static_cast<double>(d.z) * d.z);
}

// Mean luminance of an environment image over the sphere of directions (pixels weighted by
// the solid angle of their row).
double env_mean_luminance(const RgbImage& image) {
  double sum = 0, solid_angle = 0;
  for (int y = 0; y < image.height; ++y) {
    const double sin_theta = std::sin((y + 0.5) * M_PI / image.height);
    for (int x = 0; x < image.width; ++x) {
      const Rgb& c = image.pixels[static_cast<size_t>(y) * image.width + x];
      sum += luminance(vmax(c, Rgb(0.0f))) * sin_theta;
      solid_angle += sin_theta;
    }
  }
  return solid_angle > 0 ? sum / solid_angle : 0.0;
}

// Selection weights from power estimates. A light whose estimate is not a positive number
// (a black light, or a distant one in a scene without shapes) gets the mean of the others, so
// that no light that may contribute is left with probability 0.
std::vector<float> selection_weights(const std::vector<double>& power) {
  double sum = 0;
  int counted = 0;
  for (const double p : power) {
    if (p > 0 && std::isfinite(p)) {
      sum += p;
      ++counted;
    }
  }
  const double fallback = counted > 0 ? sum / counted : 1.0;
  std::vector<float> weights(power.size());
  for (size_t i = 0; i < power.size(); ++i) {
    const double p = power[i] > 0 && std::isfinite(power[i]) ? power[i] : fallback;
    // Relative to the mean, so that float keeps every weight whatever the scene's units.
    weights[i] = static_cast<float>(p / fallback);
  }
  return weights;
}

}  // namespace

LightTable::LightTable(const Scene& scene, LightSelection selection)
    : scene_(&scene),
      lights_(scene.lights),
      cone_cos_(lights_.size(), 1.0f),
      area_of_light_(lights_.size(), -1),
      light_of_shape_(scene.shapes.size(), -1),
      env_of_light_(lights_.size(), -1) {
  if (lights_.empty()) return;
  for (size_t i = 0; i < lights_.size(); ++i) {
    const Light& light = lights_[i];
    if (is_escaping(light.kind)) escaping_.push_back(static_cast<int>(i));
    switch (light.kind) {
      case LightKind::kDirectional:
      case LightKind::kPoint:
      case LightKind::kSpot:
        has_delta_ = true;
        break;
      case LightKind::kCone:
        cone_cos_[i] = std::cos(light.half_angle);
        break;
      case LightKind::kConstantEnv:
        break;
      case LightKind::kEnvMap: {
        EnvMap env;
        env.image = &scene.env_images[light.env_image];
        env.distribution = env_distribution(*env.image);
        env.to_world = light.env_rotation;
        env.to_map = inverse_rotation(light.env_rotation);
        env_of_light_[i] = static_cast<int>(envs_.size());
        envs_.push_back(std::move(env));
        break;
      }
      case LightKind::kArea: {
        const Shape& shape = scene.shapes[light.shape];
        AreaLight area;
        area.shape = light.shape;
        if (shape.kind == ShapeKind::kSphere) {
          area.total_area = 4.0f * kPi * shape.radius * shape.radius;
        } else {
          std::vector<float> areas(shape.mesh.triangle_count());
          for (size_t t = 0; t < areas.size(); ++t) {
            const Vec3 p0 = triangle_vertex(shape.mesh, t, 0);
            const Vec3 e1 = triangle_vertex(shape.mesh, t, 1) - p0;
            const Vec3 e2 = triangle_vertex(shape.mesh, t, 2) - p0;
            areas[t] = 0.5f * length(cross(e1, e2));
            area.total_area += areas[t];
          }
          area.triangles = Distribution1D(areas);
        }
        area_of_light_[i] = static_cast<int>(areas_.size());
        light_of_shape_[light.shape] = static_cast<int>(i);
        areas_.push_back(std::move(area));
        break;
      }
    }
  }
  std::vector<float> weights(lights_.size(), 1.0f);
  if (selection == LightSelection::kPower) {
    const double radius = scene_radius(scene);
    std::vector<double> power(lights_.size());
    for (size_t i = 0; i < lights_.size(); ++i) {
      power[i] = estimated_power(static_cast<int>(i), radius);
    }
    weights = selection_weights(power);
  }
  selection_ = AliasTable(weights);
}

double LightTable::estimated_power(int light, double radius) const {
  const Light& l = lights_[light];
  // Distant lights: the power their radiance carries through a disk of the scene's radius
  // facing each direction, pi R^2 times the radiance integrated over the sphere.
  const double disk = M_PI * radius * radius;
  switch (l.kind) {
    case LightKind::kDirectional:
      return luminance(l.irradiance) * disk;
    case LightKind::kCone:
      return luminance(l.radiance) * 2.0 * M_PI * (1.0 - cone_cos_[light]) * disk;
    case LightKind::kConstantEnv:
      return luminance(l.radiance) * 4.0 * M_PI * disk;
    case LightKind::kEnvMap:
      return luminance(l.radiance) * env_mean_luminance(*envs_[env_of_light_[light]].image) * 4.0 *
             M_PI * disk;
    case LightKind::kPoint:
      return luminance(l.intensity) * 4.0 * M_PI;
    case LightKind::kSpot:
      // The smoothstep falloff integrates to half its band of cosines, so the solid angle is
      // exactly 2 pi (1 - (cos_outer + cos_inner) / 2).
      return luminance(l.intensity) * 2.0 * M_PI *
             (1.0 - 0.5 * (static_cast<double>(l.spot_cos_outer) + l.spot_cos_inner));
    case LightKind::kArea:
      // One-sided Lambertian emitter: radiance * area * pi.
      return luminance(scene_->shapes[l.shape].emission) *
             areas_[area_of_light_[light]].total_area * M_PI;
  }
  return 0;
}

LightSample LightTable::sample(Vec3 p, float u_select, Vec2 u) const {
  LightSample s;
  if (lights_.empty()) return s;
  float selection_pmf = 0, u_rest = 0;
  const int index = selection_.sample(u_select, &selection_pmf, &u_rest);
  const Light& light = lights_[index];
  switch (light.kind) {
    case LightKind::kDirectional:
      s.wi = light.direction;
      s.radiance = light.irradiance;
      s.pdf = selection_pmf;
      s.delta = true;
      break;
    case LightKind::kPoint:
    case LightKind::kSpot: {
      const Vec3 to_light = light.position - p;
      s.distance = length(to_light);
      if (!(s.distance > 0)) return s;
      s.wi = to_light / s.distance;
      s.radiance = light.intensity / (s.distance * s.distance);
      if (light.kind == LightKind::kSpot) {
        s.radiance *=
            smoothstep(light.spot_cos_outer, light.spot_cos_inner, -dot(s.wi, light.spot_axis));
      }
      s.pdf = selection_pmf;
      s.delta = true;
      break;
    }
    case LightKind::kCone:
    case LightKind::kConstantEnv:
    case LightKind::kEnvMap:
      s.wi = sample_escaping(index, u);
      s.radiance = escaped_radiance(s.wi);
      s.pdf = escaped_pdf(s.wi);
      break;
    case LightKind::kArea:
      // What is left of u_select after choosing the light picks the triangle.
      s = sample_area(index, selection_pmf, p, u_rest, u);
      break;
  }
  s.valid = s.pdf > 0 && std::isfinite(s.pdf) && !is_black(s.radiance);
  s.light = index;
  return s;
}

Vec3 LightTable::sample_escaping(int light, Vec2 u) const {
  const Light& l = lights_[light];
  switch (l.kind) {
    case LightKind::kCone:
      return Frame::from_normal(l.direction).to_world(sample_uniform_cone(u, cone_cos_[light]));
    case LightKind::kEnvMap: {
      const EnvMap& env = envs_[env_of_light_[light]];
      float pdf_uv = 0;
      const Vec2 uv = env.distribution.sample(u, &pdf_uv);
      return normalize(env.to_world.vector(uv_to_map_direction(uv)));
    }
    default:
      return sample_uniform_sphere(u);
  }
}

LightSample LightTable::sample_area(int light, float selection_pmf, Vec3 p, float u_triangle,
                                    Vec2 u) const {
  LightSample s;
  const AreaLight& area = areas_[area_of_light_[light]];
  const Shape& shape = scene_->shapes[area.shape];
  Vec3 q, n;
  if (shape.kind == ShapeKind::kSphere) {
    // Uniform over the cone of directions that see the sphere; from inside, only the back side
    // is visible, which emits nothing.
    const float cos_max = visible_cone_cos(shape, p);
    if (cos_max >= 1.0f) return s;
    const Vec3 to_center = shape.center - p;
    const float dc = length(to_center);
    const Vec3 local = sample_uniform_cone(u, cos_max);
    s.wi = Frame::from_normal(to_center / dc).to_world(local);
    const float sin2 = std::max(0.0f, 1.0f - local.z * local.z);
    const float disc = shape.radius * shape.radius - dc * dc * sin2;
    if (disc < 0) return s;
    s.distance = dc * local.z - std::sqrt(disc);
    q = p + s.wi * s.distance;
    n = normalize(q - shape.center);
    s.pdf = selection_pmf * uniform_cone_pdf(cos_max);
  } else {
    if (!(area.total_area > 0)) return s;
    const int triangle = area.triangles.sample_discrete(u_triangle, nullptr);
    const Vec3 p0 = triangle_vertex(shape.mesh, triangle, 0);
    const Vec3 p1 = triangle_vertex(shape.mesh, triangle, 1);
    const Vec3 p2 = triangle_vertex(shape.mesh, triangle, 2);
    const float su = std::sqrt(u.x);
    const float b0 = 1.0f - su, b1 = u.y * su;
    q = p0 * b0 + p1 * b1 + p2 * (1.0f - b0 - b1);
    n = normalize(cross(p1 - p0, p2 - p0));
    const Vec3 to_light = q - p;
    s.distance = length(to_light);
    if (!(s.distance > 0)) return s;
    s.wi = to_light / s.distance;
  }
  const float cos_light = -dot(n, s.wi);
  if (!(cos_light > 0)) return LightSample{};
  if (shape.kind == ShapeKind::kMesh) {
    s.pdf = selection_pmf * s.distance * s.distance / (area.total_area * cos_light);
  }
  s.radiance = shape.emission;
  return s;
}

Rgb LightTable::escaped_radiance(Vec3 d) const {
  Rgb sum(0.0f);
  for (const int light : escaping_) sum += escaped_radiance_of(light, d);
  return sum;
}

float LightTable::escaped_pdf(Vec3 d) const {
  float sum = 0;
  for (const int light : escaping_) sum += selection_.pmf(light) * escaped_pdf_of(light, d);
  return sum;
}

Rgb LightTable::escaped_radiance_of(int light, Vec3 d) const {
  const Light& l = lights_[light];
  switch (l.kind) {
    case LightKind::kCone:
      return dot(d, l.direction) >= cone_cos_[light] ? l.radiance : Rgb(0.0f);
    case LightKind::kEnvMap: {
      const EnvMap& env = envs_[env_of_light_[light]];
      return l.radiance * env_bilinear(*env.image, map_direction_to_uv(env.to_map.vector(d)));
    }
    default:
      return l.radiance;
  }
}

float LightTable::escaped_pdf_of(int light, Vec3 d) const {
  const Light& l = lights_[light];
  switch (l.kind) {
    case LightKind::kCone:
      return dot(d, l.direction) >= cone_cos_[light] ? uniform_cone_pdf(cone_cos_[light]) : 0.0f;
    case LightKind::kEnvMap: {
      const EnvMap& env = envs_[env_of_light_[light]];
      const Vec3 m = env.to_map.vector(d);
      // Not sqrt(1 - y^2): near the poles y rounds to 1 while x and z still resolve the angle.
      const float sin_theta = std::hypot(m.x, m.z);
      if (sin_theta == 0) return 0.0f;
      // (u,v) -> direction stretches by 2 pi in phi and pi in theta, times sin(theta).
      return env.distribution.pdf(map_direction_to_uv(m)) / (2.0f * kPi * kPi * sin_theta);
    }
    default:
      return uniform_sphere_pdf();
  }
}

Rgb LightTable::area_radiance(int shape, Vec3 n, Vec3 wi) const {
  // wi travels toward the surface; only a front (outward) side facing the viewer emits.
  return dot(n, wi) < 0 ? scene_->shapes[shape].emission : Rgb(0.0f);
}

float LightTable::area_pdf(int shape, Vec3 p, Vec3 hit, Vec3 n) const {
  const int light = light_of_shape_[shape];
  if (light < 0) return 0.0f;
  return selection_.pmf(light) * area_pdf_of(areas_[area_of_light_[light]], p, hit, n);
}

float LightTable::area_pdf_of(const AreaLight& area, Vec3 p, Vec3 hit, Vec3 n) const {
  const Shape& shape = scene_->shapes[area.shape];
  if (shape.kind == ShapeKind::kSphere) {
    const float cos_max = visible_cone_cos(shape, p);
    return cos_max < 1.0f ? uniform_cone_pdf(cos_max) : 0.0f;
  }
  if (!(area.total_area > 0)) return 0.0f;
  const Vec3 to_hit = hit - p;
  const float d2 = dot(to_hit, to_hit);
  const float cos_light = std::fabs(dot(n, to_hit)) / std::sqrt(d2);
  if (!(cos_light > 0)) return 0.0f;
  return d2 / (area.total_area * cos_light);
}

}  // namespace snee
