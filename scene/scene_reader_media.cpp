// The scene document's media: homogeneous ones and grid media with their density.
#include <optional>
#include <utility>

#include "scene/density_grid_io.h"
#include "scene/rgb_image_io.h"
#include "scene/scene_reader.h"

namespace snee::scene_reader {

using nlohmann::json;

DensityGrid SceneReader::density_grid(const JsonValue& value, json& canonical) {
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
    const uint64_t voxels = grid.voxel_count();
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

Rgb SceneReader::mean_albedo(const JsonValue& where) {
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

int SceneReader::add_medium(const JsonValue& value, bool top_level) {
  const JsonObject obj = value.object({"name", "type", "sigma_s", "sigma_a", "albedo",
                                       "albedo_texture", "mean_free_path", "g", "density"});
  const std::string type = obj.has("type") ? obj.required("type").choice({"homogeneous", "grid"})
                                           : std::string("homogeneous");
  Medium medium;
  json canonical_grid;
  if (type == "grid") {
    medium.density =
        std::make_shared<const DensityGrid>(density_grid(obj.required("density"), canonical_grid));
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

}  // namespace snee::scene_reader
