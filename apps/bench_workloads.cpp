#include "apps/bench_workloads.h"

#include <filesystem>
#include <utility>

#include <nlohmann/json.hpp>

#include "scene/scene_loader.h"

namespace snee {

namespace {

constexpr const char* kSphere = "builtin:sphere-cone-r0.04";
constexpr const char* kBunny = "builtin:bunny-cone-r0.04";

// The grid scene's medium with every coefficient scaled (same albedo, other optical size).
nlohmann::json scaled_medium(nlohmann::json doc, double factor) {
  for (nlohmann::json& medium : doc["media"]) {
    for (const char* key : {"sigma_s", "sigma_a"}) {
      for (nlohmann::json& c : medium[key]) c = c.get<double>() * factor;
    }
  }
  return doc;
}

Scene load(const nlohmann::json& doc, const std::string& origin) {
  return load_scene_json(doc, origin, SNEE_DATA_DIR).scene;
}

void add_pair(BenchWorkloads& out, const std::string& object, const std::string& what,
              const std::string& source, const Scene& scene) {
  for (const char* integrator : {"pt", "snee"}) {
    BenchWorkload w;
    w.name = object + "-" + integrator;
    w.description = what + ", " + integrator;
    w.source = source;
    w.integrator = integrator;
    w.scene = scene;
    out.workloads.push_back(std::move(w));
  }
}

}  // namespace

std::string default_dragon_path() {
  return (std::filesystem::path(SNEE_DATA_DIR) / "../../shared/data/meshes/dragon_vrip.ply")
      .lexically_normal()
      .string();
}

BenchWorkloads bench_workloads(const std::string& dragon_path, bool include_dragon) {
  BenchWorkloads out;
  const LoadedScene bunny = load_scene(kBunny);

  BenchWorkload camera;
  camera.name = "camera";
  camera.description = "camera rays only: bunny, paths end at their first hit (max depth 0)";
  camera.source = kBunny;
  camera.integrator = "pt";
  camera.max_depth = 0;
  camera.spp_factor = 16;
  camera.scene = bunny.scene;
  out.workloads.push_back(std::move(camera));

  add_pair(out, "sphere", "translucent sphere (Embree sphere primitive)", kSphere,
           load_scene(kSphere).scene);
  add_pair(out, "bunny", "translucent bunny (data/meshes/bunny-npm.obj)", kBunny, bunny.scene);

  if (!include_dragon) {
    out.skipped.push_back("dragon: skipped (--quick)");
  } else if (!std::filesystem::is_regular_file(dragon_path)) {
    out.skipped.push_back("dragon: skipped, no mesh at " + dragon_path + " (see --dragon)");
  } else {
    nlohmann::json doc = bunny.canonical;
    doc["name"] = "dragon-cone-r0.04";
    doc["shapes"][0]["file"] = std::filesystem::absolute(dragon_path).string();
    doc["shapes"][0]["name"] = "dragon";
    add_pair(out, "dragon", "translucent Stanford dragon (an open scan: paths may leak)",
             dragon_path, load(doc, "bench:dragon"));
  }

  add_pair(out, "dense", "bunny, medium 10x denser (same albedo)", kBunny,
           load(scaled_medium(bunny.canonical, 10.0), "bench:dense"));
  add_pair(out, "thin", "bunny, medium 10x thinner (same albedo)", kBunny,
           load(scaled_medium(bunny.canonical, 0.1), "bench:thin"));
  return out;
}

}  // namespace snee
