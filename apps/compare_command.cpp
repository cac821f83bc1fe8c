#include "apps/compare_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "apps/contact_sheet.h"
#include "apps/image_error.h"
#include "apps/option_checks.h"
#include "apps/resolution.h"
#include "apps/stats_json.h"
#include "scene/scene_loader.h"
#include "scheduler/render.h"

namespace snee {

namespace {

namespace fs = std::filesystem;

// Seeds of the compared renders and of the reference differ, so their noise is independent.
constexpr uint32_t kReferenceSeedOffset = 1000003;
// Pilot renders double their spp from this until one takes this share of the budget.
constexpr int kFirstPilotSpp = 2;
constexpr double kPilotShare = 0.1;
constexpr int kMaxEqualTimeSpp = 1 << 30;

struct Entry {
  std::string integrator;
  Film film;
  RenderStats stats;
  int spp = 0;
  ImageError error;
  double efficiency = 0;
  double efficiency_trimmed = 0;
};

RenderResult render_logged(const Scene& scene, RenderOptions options, bool quiet,
                           const char* role) {
  RenderResult r = render(scene, options);
  if (!quiet) {
    std::fprintf(stderr, "  %s %s: %d spp in %.2f s\n", role, options.integrator.c_str(),
                 options.spp, r.stats.seconds);
  }
  return r;
}

// The spp whose render takes `seconds`. A render's time is a fixed part (scene set-up, threads,
// the film) plus a part per sample; pilots of growing spp until one is long enough to time
// measure both from the last two, so a short pilot's set-up cost does not inflate the time per
// sample (which would hand the cheaper integrator less than its share of the time).
int equal_time_spp(const Scene& scene, RenderOptions options, double seconds, bool quiet) {
  int spp = kFirstPilotSpp;
  options.spp = spp;
  double time = render_logged(scene, options, quiet, "pilot").stats.seconds;
  int previous_spp = 0;
  double previous_time = 0;
  while (time < kPilotShare * seconds && spp < (1 << 20)) {
    previous_spp = spp;
    previous_time = time;
    spp *= 2;
    options.spp = spp;
    time = render_logged(scene, options, quiet, "pilot").stats.seconds;
  }
  const double per_spp = previous_spp > 0 && time > previous_time
                             ? (time - previous_time) / (spp - previous_spp)
                             : time / spp;
  const double fixed = std::max(0.0, time - per_spp * spp);
  // In double first: a long budget over a cheap sample would overflow an int.
  const double fitting = std::floor((seconds - fixed) / per_spp);
  return static_cast<int>(std::clamp(fitting, 1.0, static_cast<double>(kMaxEqualTimeSpp)));
}

}  // namespace

CompareCommand::CompareCommand(CLI::App& parent)
    : command_(parent.add_subcommand(
          "compare",
          "Render a scene with several integrators at equal time (or spp) against a reference "
          "and report relative MSE and efficiency")) {
  CLI::App& c = *command_;
  c.add_option("SCENE", scene_, "JSON scene file or builtin:NAME")->capture_default_str();
  c.add_option("--integrators", integrators_,
               "Comma-separated integrators; the first is the baseline of the ratios")
      ->delimiter(',')
      ->check(CLI::IsMember({"pt", "snee", "sla"}))
      ->capture_default_str();
  c.add_option("--time", seconds_, "Seconds per integrator (equal time)")
      ->check(finite_positive())
      ->capture_default_str();
  c.add_option("--spp", spp_, "Equal samples per pixel instead of equal time")
      ->check(CLI::PositiveNumber);
  c.add_option("--reference", reference_,
               "Reference EXR of the same size; without it a long render is made");
  c.add_option("--reference-spp", reference_spp_, "Samples per pixel of the made reference")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  c.add_option("--reference-integrator", reference_integrator_,
               "Integrator of the made reference (an unbiased one)")
      ->check(CLI::IsMember({"pt", "snee"}))
      ->capture_default_str();
  c.add_option("--resolution", resolution_, "Image size WxH, overriding the camera's")
      ->check(resolution_validator());
  c.add_option("--threads", threads_, "Worker threads, 0 = all")
      ->check(integer_at_least(0))
      ->capture_default_str();
  c.add_option("--seed", seed_, "Seed of the compared renders")->capture_default_str();
  c.add_option("-o,--output", output_, "Output directory")->default_str("out/compare-<scene>");
  c.add_flag("-q,--quiet", quiet_, "No progress output");
}

int CompareCommand::run() const {
  LoadedScene loaded = load_scene(scene_);
  Scene& scene = loaded.scene;
  if (const auto size = parse_resolution(resolution_)) {
    scene.camera.width = size->width;
    scene.camera.height = size->height;
  }
  if (scene.name.empty()) scene.name = "scene";  // render() stamps it on every film
  const std::string& name = scene.name;
  const fs::path dir = output_.empty() ? fs::path("out") / ("compare-" + name) : fs::path(output_);
  fs::create_directories(dir);

  RenderOptions base;
  base.threads = capped_threads(threads_);
  base.seed = seed_;
  base.max_depth = scene.render.max_depth;

  Film reference;
  if (!reference_.empty()) {
    reference = read_exr(reference_);
  } else {
    RenderOptions ro = base;
    ro.integrator = reference_integrator_;
    ro.spp = reference_spp_;
    ro.seed = seed_ + kReferenceSeedOffset;
    RenderResult r = render_logged(scene, ro, quiet_, "reference");
    reference = std::move(r.film);
    write_exr(reference, (dir / "reference.exr").string());
  }

  std::vector<Entry> entries;
  for (const std::string& integrator : integrators_) {
    RenderOptions o = base;
    o.integrator = integrator;
    if (spp_ > 0) {
      o.spp = spp_;
    } else {
      o.spp = equal_time_spp(scene, o, seconds_, quiet_);
    }
    RenderResult r = render_logged(scene, o, quiet_, "render");
    Entry e;
    e.integrator = integrator;
    e.film = std::move(r.film);
    e.stats = r.stats;
    e.spp = o.spp;
    e.error = image_error(e.film, reference);
    e.efficiency = e.error.relative_mse > 0 ? 1.0 / (e.error.relative_mse * e.stats.seconds) : 0;
    e.efficiency_trimmed = e.error.relative_mse_trimmed > 0
                               ? 1.0 / (e.error.relative_mse_trimmed * e.stats.seconds)
                               : 0;
    write_exr(e.film, (dir / (integrator + ".exr")).string());
    entries.push_back(std::move(e));
  }

  const double baseline = entries.front().efficiency;
  const double baseline_trimmed = entries.front().efficiency_trimmed;
  nlohmann::ordered_json report = {
      {"scene", name},
      {"resolution", {reference.width, reference.height}},
      {"mode", spp_ > 0 ? "equal-spp" : "equal-time"},
      {"budget_seconds", spp_ > 0 ? 0.0 : seconds_},
      {"reference",
       {{"file", reference_.empty() ? (dir / "reference.exr").string() : reference_},
        {"spp", reference.meta.spp},
        {"integrator", reference.meta.integrator}}},
      {"relative_mse_floor", kRelativeMseFloor},
      {"integrators", nlohmann::ordered_json::array()}};
  std::printf("%-6s %8s %9s %12s %12s %12s %10s %10s\n", "integ.", "spp", "seconds", "relMSE",
              "trimmed", "efficiency", "vs first", "(trimmed)");
  std::vector<const Film*> films;
  std::vector<Film> errors;
  for (const Entry& e : entries) {
    const double ratio = baseline > 0 ? e.efficiency / baseline : 0;
    const double ratio_trimmed = baseline_trimmed > 0 ? e.efficiency_trimmed / baseline_trimmed : 0;
    std::printf("%-6s %8d %9.2f %12.4e %12.4e %12.4e %10.3f %10.3f\n", e.integrator.c_str(), e.spp,
                e.stats.seconds, e.error.relative_mse, e.error.relative_mse_trimmed, e.efficiency,
                ratio, ratio_trimmed);
    report["integrators"].push_back({{"name", e.integrator},
                                     {"spp", e.spp},
                                     {"seconds", e.stats.seconds},
                                     {"relative_mse", e.error.relative_mse},
                                     {"relative_mse_raw", e.error.relative_mse_raw},
                                     {"reference_noise", e.error.reference_noise},
                                     {"relative_mse_trimmed", e.error.relative_mse_trimmed},
                                     {"efficiency_trimmed", e.efficiency_trimmed},
                                     {"efficiency_trimmed_vs_first", ratio_trimmed},
                                     {"efficiency", e.efficiency},
                                     {"efficiency_vs_first", ratio},
                                     {"mrays_per_second", e.stats.mrays_per_second()},
                                     {"file", (dir / (e.integrator + ".exr")).string()}});
    films.push_back(&e.film);
    errors.push_back(error_image(e.film, reference));
  }
  const fs::path sheet = dir / "contact-sheet.png";
  write_preview(contact_sheet(reference, films, errors), sheet.string());
  write_json_file(report, (dir / "compare.json").string());
  std::printf("wrote %s\nwrote %s\n", sheet.c_str(), (dir / "compare.json").c_str());
  return 0;
}

}  // namespace snee
