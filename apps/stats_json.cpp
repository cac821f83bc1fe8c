#include "apps/stats_json.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace snee {

nlohmann::ordered_json ray_counts_json(const RenderStats& stats) {
  nlohmann::ordered_json rays = nlohmann::ordered_json::object();
  for (int k = 0; k < static_cast<int>(RayKind::kCount); ++k)
    rays[ray_kind_name(static_cast<RayKind>(k))] = stats.rays[k];
  rays["total"] = stats.total_rays();
  return rays;
}

nlohmann::ordered_json stage_seconds_json(const RenderStats& stats) {
  nlohmann::ordered_json stages = nlohmann::ordered_json::object();
  for (int s = 0; s < static_cast<int>(Stage::kCount); ++s)
    stages[stage_name(static_cast<Stage>(s))] = stats.stage_seconds[s];
  return stages;
}

nlohmann::ordered_json simd_lanes_json(const RenderStats& stats) {
  const auto lanes = [](const LaneCount& c) {
    return nlohmann::ordered_json{
        {"active_lanes", c.active}, {"lanes_run", c.run}, {"occupancy", c.occupancy()}};
  };
  nlohmann::ordered_json kernels = nlohmann::ordered_json::object();
  for (int k = 0; k < kBatchedKernels; ++k)
    kernels[batched_kernel_name(static_cast<BatchedKernel>(k))] = lanes(stats.simd_lanes[k]);
  return {{"level", simd_level_name(stats.simd_level)},
          {"width", stats.simd_width},
          {"lane_occupancy", stats.all_simd_lanes().occupancy()},
          {"kernels", kernels}};
}

namespace {

nlohmann::ordered_json processes_json(const std::vector<ProcessShare>& processes) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const ProcessShare& p : processes) {
    all.push_back({{"threads", p.threads},
                   {"tiles", p.tiles},
                   {"busy_seconds", p.busy_seconds},
                   {"join_seconds", p.join_seconds}});
  }
  return all;
}

}  // namespace

nlohmann::ordered_json stats_json(const std::string& scene, const RenderOptions& options,
                                  const RenderResult& result, bool tile_seconds) {
  const RenderStats& stats = result.stats;
  nlohmann::ordered_json snee = nlohmann::ordered_json::object();
  snee["engaged"] = stats.snee_engaged;
  snee["smallest_light_half_angle_degrees"] = stats.smallest_light_degrees;
  snee["strategies_run"] = stats.snee_engaged ? strategy_set_name(stats.snee_strategies) : "";
  for (int c = 0; c < kSneeCounterCount; ++c)
    snee[snee_counter_name(static_cast<SneeCounter>(c))] = stats.snee[c];

  nlohmann::ordered_json json = {
      {"version", SNEE_VERSION},
      {"scene", scene},
      {"integrator", options.integrator},
      {"spp", options.spp},
      {"complete", result.complete},
      {"min_spp", result.film.meta.min_spp},
      {"seed", options.seed},
      {"threads", stats.threads},
      {"resolution", {{"width", result.film.width}, {"height", result.film.height}}},
      {"max_depth", options.max_depth},
      {"queue_capacity", options.queue_capacity},
      {"tile_size", options.tile_size},
      {"samples_per_unit", options.samples_per_unit},
      {"schedule", options.schedule},
      {"seconds", stats.seconds},
      {"sampling_seconds", stats.sampling_seconds},
      {"sampling_cpu_seconds", stats.sampling_cpu_seconds},
      {"stage_seconds", stage_seconds_json(stats)},
      {"rays", ray_counts_json(stats)},
      {"paths", stats.paths},
      {"nonfinite_samples", stats.nonfinite_samples},
      {"shortest_free_path_clearances",
       std::isfinite(stats.shortest_free_path.clearances)
           ? nlohmann::ordered_json(stats.shortest_free_path.clearances)
           : nlohmann::ordered_json(nullptr)},
      {"mrays_per_second", stats.mrays_per_second()},
      {"path_state_bytes_per_slot", stats.path_state_bytes_per_slot},
      {"queue_occupancy", stats.queue_occupancy},
      {"simd", simd_lanes_json(stats)},
      {"snee_options", snee_options_json(options.snee)},
      {"snee", snee},
  };
  if (!stats.processes.empty()) json["processes"] = processes_json(stats.processes);
  if (tile_seconds) json["tile_seconds"] = stats.tile_seconds;
  return json;
}

nlohmann::ordered_json snee_options_json(const SneeOptions& snee) {
  return {{"probe", probe_directions_name(snee.probe)},
          {"distance_mix", snee.c_exponential},
          {"joint_mix", snee.c_joint},
          {"heuristic", snee.heuristic == MisHeuristic::kPower ? "power" : "balance"},
          {"strategies", strategy_set_name(snee.enabled)},
          {"light_limit_degrees", snee.light_limit_degrees},
          {"reflection_chains", snee.reflection_chains},
          {"mesh_chain_levels", snee.mesh_chain_levels},
          {"probe_rate", snee.probe_rate},
          {"manifold_rate", snee.manifold_rate},
          {"guide_rate", snee.guide_rate},
          {"guide_cap_degrees", snee.guide_cap_degrees}};
}

void write_json_file(const nlohmann::ordered_json& json, const std::string& path) {
  errno = 0;
  std::ofstream out(path);
  out << json.dump(2) << '\n';
  out.close();
  if (!out)
    throw std::runtime_error("cannot write '" + path + "'" +
                             (errno != 0 ? std::string(": ") + std::strerror(errno) : ""));
}

std::string nonfinite_warning(const RenderStats& stats) {
  if (stats.nonfinite_samples == 0) return "";
  const double percent = stats.paths > 0 ? 100.0 * static_cast<double>(stats.nonfinite_samples) /
                                               static_cast<double>(stats.paths)
                                         : 100.0;
  char text[200];
  std::snprintf(text, sizeof text,
                "warning: %llu of %llu samples (%.3g%%) were not finite (NaN or infinite) and "
                "count as 0 in the image",
                static_cast<unsigned long long>(stats.nonfinite_samples),
                static_cast<unsigned long long>(stats.paths), percent);
  return text;
}

std::string dense_medium_warning(const ShortestFreePath& shortest) {
  if (!(shortest.clearances < kFreePathClearancesForAccuracy)) return "";
  const std::string name = shortest.medium.empty() ? "a medium" : "'" + shortest.medium + "'";
  char text[640];
  std::snprintf(text, sizeof text,
                "warning: the mean free path of medium %s is only %.3g times the ray clearance "
                "(float precision at this scene's size): walks near its boundary are distorted "
                "and it renders too dark (about 2%% at 10 times, 25%% at 1; docs/reliability.md); "
                "a longer mean free path avoids it, as do shapes nearer the origin (the "
                "clearance grows with the largest coordinate); scaling the whole scene does not",
                name.c_str(), shortest.clearances);
  return text;
}

std::string grid_media_note(const RenderOptions& options, const Scene& scene) {
  if (options.integrator != "snee") return "";
  std::string names;
  for (const Medium& m : scene.media) {
    if (m.density) names += (names.empty() ? "'" : ", '") + m.name + "'";
  }
  if (names.empty()) return "";
  return "note: snee samples the grid media " + names +
         " as pt does: SNEE's samplers need a homogeneous medium (docs/method.md 4.8)";
}

std::string snee_engagement_note(const RenderOptions& options, const RenderStats& stats) {
  if (options.integrator != "snee" || stats.snee_engaged) return "";
  char text[300];
  std::snprintf(text, sizeof text,
                "note: snee ran as pt: the smallest light fills a cone of %.3g degrees, more "
                "than --snee-light-limit %.3g, and the path tracer finds such lights by itself "
                "(docs/method.md 3.11); --snee-light-limit 180 runs SNEE anyway",
                stats.smallest_light_degrees, options.snee.light_limit_degrees);
  return text;
}

}  // namespace snee
