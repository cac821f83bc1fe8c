#include "apps/scale_command.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "apps/measure_render.h"
#include "apps/resolution.h"
#include "apps/scale_plot.h"
#include "apps/simd_option.h"
#include "apps/stats_json.h"
#include "apps/thread_counts.h"
#include "scene/scene_loader.h"

namespace snee {

namespace {

void write_text_file(const std::string& text, const std::string& path) {
  errno = 0;
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out)
    throw std::runtime_error("cannot write '" + path + "'" +
                             (errno != 0 ? std::string(": ") + std::strerror(errno) : ""));
}

}  // namespace

ScaleCommand::ScaleCommand(CLI::App& parent)
    : command_(parent.add_subcommand(
          "scale", "Measure speedup and parallel efficiency over a list of thread counts")) {
  CLI::App& c = *command_;
  c.add_option("SCENE", scene_, "JSON scene file or builtin:NAME")->capture_default_str();
  c.add_option("--threads", threads_, "Comma-separated thread counts, e.g. 1,2,4")
      ->check(thread_counts_validator())
      ->capture_default_str();
  c.add_option("--repeats", repeats_, "Renders per thread count; the median is reported")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  c.add_option("--spp", spp_, "Samples per pixel")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  c.add_option("--resolution", resolution_, "Image size WxH [default: the scene's]")
      ->check(resolution_validator());
  c.add_option("--integrator", integrator_, "pt, snee or sla [default: the scene's]")
      ->check(CLI::IsMember({"pt", "snee", "sla"}));
  add_simd_option(c, simd_);
  c.add_option("--schedule", schedule_, "megakernel, local or global")
      ->check(CLI::IsMember({"megakernel", "local", "global"}))
      ->capture_default_str();
  c.add_option("--json", json_, "Also write the results as JSON to this file");
  c.add_option("--plot", plot_, "Also draw speedup and efficiency as an SVG to this file");
}

int ScaleCommand::run() const {
  LoadedScene loaded = load_scene(scene_);
  for (const std::string& warning : loaded.warnings)
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
  Scene& scene = loaded.scene;
  if (const auto size = parse_resolution(resolution_)) {
    scene.camera.width = size->width;
    scene.camera.height = size->height;
  }
  RenderOptions options;
  options.spp = spp_;
  options.seed = scene.render.seed;
  options.max_depth = scene.render.max_depth;
  options.integrator = given("--integrator") ? integrator_ : scene.render.integrator;
  options.schedule = schedule_;
  options.simd = simd_;
  const std::vector<int> threads = capped_thread_counts(*parse_thread_counts(threads_));

  std::printf(
      "snee scale %s: %s, %s schedule, %dx%d, %d spp, %d repeat(s), %u hardware threads, %s\n",
      scene_.c_str(), options.integrator.c_str(), schedule_.c_str(), scene.camera.width,
      scene.camera.height, options.spp, repeats_, std::thread::hardware_concurrency(),
      simd_choice_text(simd_, schedule_).c_str());
  // Repeats are interleaved over the thread counts, so a burst of other work on the machine
  // does not land on one count alone.
  std::vector<Measurement> measurements(threads.size());
  for (int r = 0; r < repeats_; ++r) {
    for (size_t i = 0; i < threads.size(); ++i) {
      options.threads = threads[i];
      measurements[i].repeat(scene, options);
    }
  }

  // Speedup is measured from the smallest thread count, scaled so that ideal scaling reads n.
  size_t base = 0;
  for (size_t i = 0; i < threads.size(); ++i) {
    if (threads[i] < threads[base]) base = i;
  }
  const double base_seconds = measurements[base].median().sampling_seconds * threads[base];
  const double base_cpu_seconds = measurements[base].median().sampling_cpu_seconds;
  std::vector<ScalePoint> points;
  nlohmann::ordered_json results = nlohmann::ordered_json::array();
  std::printf("%7s %10s %10s %10s %6s %11s %8s %10s %10s\n", "threads", "seconds", "min", "max",
              "cpu%", "paths/s", "speedup", "efficiency", "cpu-effic");
  for (size_t i = 0; i < threads.size(); ++i) {
    const Measurement& m = measurements[i];
    const RenderStats& s = m.median();
    const std::vector<double> repeat_seconds = m.sampling_seconds();
    const double speedup = s.sampling_seconds > 0 ? base_seconds / s.sampling_seconds : 0;
    const double efficiency = speedup / threads[i];
    const double work_efficiency =
        s.sampling_cpu_seconds > 0 ? base_cpu_seconds / s.sampling_cpu_seconds : 0;
    const MeasurementCheck check =
        check_measurement(s.sampling_seconds, s.sampling_cpu_seconds, threads[i]);
    const double cpu_share = check.cpu_share;
    for (const std::string& warning : check.warnings)
      std::fprintf(stderr, "warning: %d thread(s): %s\n", threads[i], warning.c_str());
    const double paths_per_second =
        s.sampling_seconds > 0 ? static_cast<double>(s.paths) / s.sampling_seconds : 0;
    points.push_back({threads[i], speedup, efficiency, work_efficiency});
    std::printf("%7d %10.3f %10.3f %10.3f %5.0f%% %11.0f %7.2fx %9.1f%% %9.1f%%\n", threads[i],
                s.sampling_seconds, *std::min_element(repeat_seconds.begin(), repeat_seconds.end()),
                *std::max_element(repeat_seconds.begin(), repeat_seconds.end()), 100 * cpu_share,
                paths_per_second, speedup, 100 * efficiency, 100 * work_efficiency);
    results.push_back(
        {{"threads", threads[i]},
         {"seconds", s.sampling_seconds},
         {"repeat_seconds", repeat_seconds},
         {"cpu_seconds", s.sampling_cpu_seconds},
         {"repeat_cpu_seconds", m.sampling_cpu_seconds()},
         {"cpu_share", cpu_share},
         {"warnings", check.warnings},
         {"paths", s.paths},
         {"paths_per_second", paths_per_second},
         {"mrays_per_second", s.sampling_seconds > 0
                                  ? static_cast<double>(s.total_rays()) / s.sampling_seconds * 1e-6
                                  : 0},
         {"speedup", speedup},
         {"efficiency", efficiency},
         {"work_efficiency", work_efficiency},
         {"stage_seconds", stage_seconds_json(s)},
         {"peak_memory_mib", m.peak_memory_mib()}});
  }

  if (!json_.empty()) {
    const nlohmann::ordered_json json = {
        {"version", SNEE_VERSION},
        {"scene", scene_},
        {"integrator", options.integrator},
        {"schedule", schedule_},
        {"spp", options.spp},
        {"resolution", {{"width", scene.camera.width}, {"height", scene.camera.height}}},
        {"repeats", repeats_},
        {"hardware_threads", std::thread::hardware_concurrency()},
        {"results", results},
    };
    write_json_file(json, json_);
    std::printf("wrote %s\n", json_.c_str());
  }
  if (!plot_.empty()) {
    const std::string subtitle = scene_ + ", " + options.integrator + ", " + schedule_ +
                                 " schedule, " + std::to_string(scene.camera.width) + "x" +
                                 std::to_string(scene.camera.height) + ", " +
                                 std::to_string(options.spp) + " spp, median of " +
                                 std::to_string(repeats_) + " run(s) per point";
    write_text_file(scale_plot_svg(points, "snee scale: speedup and parallel efficiency", subtitle),
                    plot_);
    std::printf("wrote %s\n", plot_.c_str());
  }
  return 0;
}

}  // namespace snee
