#include "apps/compare_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/contact_sheet.h"
#include "apps/equal_time_plan.h"
#include "apps/image_error.h"
#include "apps/labelled_preview.h"
#include "apps/option_checks.h"
#include "apps/output_files.h"
#include "apps/progress_bar.h"
#include "apps/resolution.h"
#include "apps/simd_option.h"
#include "apps/stats_json.h"
#include "scene/scene_loader.h"
#include "scheduler/render.h"

namespace snee {

namespace {

namespace fs = std::filesystem;

// Seeds of the compared renders and of the reference differ, so their noise is independent.
constexpr uint32_t kReferenceSeedOffset = 1000003;
// Pilot renders double their spp from this until one samples for this share of the budget.
constexpr int kFirstPilotSpp = 2;
constexpr double kPilotShare = 0.05;
constexpr int kMostPilotSpp = 1 << 20;

struct Entry {
  std::string integrator;
  Film film;
  RenderStats stats;
  int spp = 0;
  int samples_per_round = 0;
  ImageError error;
  double efficiency = 0;
  double efficiency_trimmed = 0;
};

// One render with its progress on stderr under `label`, then a line saying what it took.
RenderResult render_shown(const Scene& scene, const RenderOptions& options, bool quiet,
                          const std::string& label) {
  ProgressBar bar(stderr, label, options.time_seconds);
  RenderHooks hooks;
  if (!quiet) hooks.progress = [&bar](const Progress& p) { bar.update(p); };
  RenderResult r = render(scene, options, hooks);
  bar.finish();
  if (!quiet) {
    std::fprintf(stderr, "  %s: %d spp in %.2f s\n", label.c_str(), r.film.meta.min_spp,
                 r.stats.seconds);
  }
  return r;
}

// Sampling seconds per spp, from pilots of doubling spp until one samples long enough to time.
double seconds_per_spp(const Scene& scene, RenderOptions options, double budget, bool quiet) {
  for (int spp = kFirstPilotSpp;; spp *= 2) {
    options.spp = spp;
    const RenderStats stats =
        render_shown(scene, options, quiet, options.integrator + " pilot").stats;
    if (stats.sampling_seconds >= kPilotShare * budget || spp >= kMostPilotSpp)
      return stats.sampling_seconds / spp;
  }
}

// The reference must match the renders pixel for pixel; finding out after they ran would
// waste the whole budget.
Film read_reference(const std::string& file, const Scene& scene) {
  Film reference = read_exr(file);
  const int w = scene.camera.width, h = scene.camera.height;
  if (reference.width != w || reference.height != h) {
    throw std::invalid_argument(
        "--reference " + file + ": the reference is " + std::to_string(reference.width) + "x" +
        std::to_string(reference.height) + " but the renders would be " + std::to_string(w) + "x" +
        std::to_string(h) + " (the scene's camera or --resolution); give --resolution " +
        std::to_string(reference.width) + "x" + std::to_string(reference.height) +
        " or a reference of the renders' size");
  }
  return reference;
}

// The font of the contact sheet's labels: the one given (which must draw), else the first
// default found, else none, said once up front.
std::optional<fs::path> label_font(const std::string& given, bool quiet) {
  if (!given.empty()) {
    check_label_font(given);
    return fs::path(given);
  }
  const std::vector<fs::path> candidates = default_label_fonts();
  std::optional<fs::path> font = find_label_font(candidates);
  if (!font && !quiet) {
    std::string tried;
    for (const fs::path& c : candidates) tried += " " + c.string();
    std::fprintf(stderr,
                 "warning: no font for the contact sheet's labels (looked for%s; install "
                 "fonts-dejavu-core or give --font FILE.ttf): the sheet is written without "
                 "them\n",
                 tried.c_str());
  }
  return font;
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
  c.add_option("--light-selection", light_selection_,
               "Light selection of every render, the made reference's too: uniform or power "
               "(docs/lights.md) [default: the scene's render.light_selection, else uniform]")
      ->check(CLI::IsMember({"uniform", "power"}));
  c.add_option("--threads", threads_, "Worker threads, 0 = all")
      ->check(integer_at_least(0))
      ->capture_default_str();
  add_simd_option(c, simd_);
  c.add_option("--seed", seed_, "Seed of the compared renders")->capture_default_str();
  c.add_option("-o,--output", output_, "Output directory")->default_str("out/compare-<scene>");
  c.add_option("--font", font_,
               "TrueType font of the contact sheet's labels [default: DejaVu Sans from the "
               "system's fonts; without one the sheet has no labels]");
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
  // Everything that can be wrong with the inputs is found before the first sample.
  Film reference;
  if (!reference_.empty()) reference = read_reference(reference_, scene);
  const std::optional<fs::path> font = label_font(font_, quiet_);
  const fs::path sheet_file = dir / "contact-sheet.png";
  check_destination(sheet_file, 0);

  RenderOptions base;
  base.threads = capped_threads(threads_);
  base.seed = seed_;
  base.simd = simd_;
  base.max_depth = scene.render.max_depth;
  base.light_selection = light_selection_.empty() ? scene.render.light_selection
                                                  : *parse_light_selection(light_selection_);

  if (reference_.empty()) {
    RenderOptions ro = base;
    ro.integrator = reference_integrator_;
    ro.spp = reference_spp_;
    ro.seed = seed_ + kReferenceSeedOffset;
    RenderResult r = render_shown(scene, ro, quiet_, "reference " + ro.integrator);
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
      const EqualTimePlan plan =
          plan_equal_time(seconds_, seconds_per_spp(scene, o, seconds_, quiet_));
      o.spp = plan.max_spp;
      o.samples_per_unit = plan.samples_per_unit;
      o.time_seconds = plan.time_seconds;
    }
    RenderResult r = render_shown(scene, o, quiet_, integrator);
    Entry e;
    e.integrator = integrator;
    e.film = std::move(r.film);
    e.stats = r.stats;
    e.spp = e.film.meta.min_spp;
    e.samples_per_round = o.samples_per_unit;
    e.error = image_error(e.film, reference);
    e.efficiency = e.error.relative_mse > 0 ? 1.0 / (e.error.relative_mse * e.stats.seconds) : 0;
    e.efficiency_trimmed = e.error.relative_mse_trimmed > 0
                               ? 1.0 / (e.error.relative_mse_trimmed * e.stats.seconds)
                               : 0;
    if (spp_ == 0 && !within_budget(e.stats.seconds, seconds_)) {
      std::fprintf(stderr,
                   "warning: %s took %.2f s of its %g s budget, more than %.0f%% off (a round of "
                   "%d spp took %.2f s; other work on the machine changes the time too)\n",
                   integrator.c_str(), e.stats.seconds, seconds_, 100 * kBudgetTolerance,
                   o.samples_per_unit,
                   e.spp > 0 ? e.stats.sampling_seconds * o.samples_per_unit / e.spp : 0.0);
    }
    write_exr(e.film, (dir / (integrator + ".exr")).string());
    entries.push_back(std::move(e));
  }

  const double baseline = entries.front().efficiency;
  const double baseline_trimmed = entries.front().efficiency_trimmed;
  const bool equal_time = spp_ == 0;
  nlohmann::ordered_json report = {
      {"scene", name},
      {"resolution", {reference.width, reference.height}},
      {"mode", equal_time ? "equal-time" : "equal-spp"},
      {"budget_seconds", equal_time ? seconds_ : 0.0},
      {"budget_tolerance", kBudgetTolerance},
      {"reference",
       {{"file", reference_.empty() ? (dir / "reference.exr").string() : reference_},
        {"spp", reference.meta.spp},
        {"integrator", reference.meta.integrator}}},
      {"relative_mse_floor", kRelativeMseFloor},
      {"integrators", nlohmann::ordered_json::array()}};
  std::printf("%-6s %8s %9s %12s %12s %12s %10s %10s\n", "integ.", "spp", "seconds", "relMSE",
              "trimmed", "efficiency", "vs first", "(trimmed)");
  std::vector<SheetRender> sheet_renders;
  for (const Entry& e : entries) {
    const double ratio = baseline > 0 ? e.efficiency / baseline : 0;
    const double ratio_trimmed = baseline_trimmed > 0 ? e.efficiency_trimmed / baseline_trimmed : 0;
    std::printf("%-6s %8d %9.2f %12.4e %12.4e %12.4e %10.3f %10.3f\n", e.integrator.c_str(), e.spp,
                e.stats.seconds, e.error.relative_mse, e.error.relative_mse_trimmed, e.efficiency,
                ratio, ratio_trimmed);
    nlohmann::ordered_json entry = {{"name", e.integrator},
                                    {"spp", e.spp},
                                    {"seconds", e.stats.seconds},
                                    {"sampling_seconds", e.stats.sampling_seconds}};
    if (equal_time) {
      entry["samples_per_round"] = e.samples_per_round;
      entry["budget_share"] = e.stats.seconds / seconds_;
      entry["within_budget"] = within_budget(e.stats.seconds, seconds_);
    }
    entry.update(nlohmann::ordered_json{{"relative_mse", e.error.relative_mse},
                                        {"relative_mse_raw", e.error.relative_mse_raw},
                                        {"reference_noise", e.error.reference_noise},
                                        {"relative_mse_trimmed", e.error.relative_mse_trimmed},
                                        {"efficiency_trimmed", e.efficiency_trimmed},
                                        {"efficiency_trimmed_vs_first", ratio_trimmed},
                                        {"efficiency", e.efficiency},
                                        {"efficiency_vs_first", ratio},
                                        {"mrays_per_second", e.stats.mrays_per_second()},
                                        {"file", (dir / (e.integrator + ".exr")).string()}});
    report["integrators"].push_back(std::move(entry));
    sheet_renders.push_back({e.integrator, &e.film, error_image(e.film, reference), e.spp,
                             e.stats.seconds, e.error.relative_mse});
  }
  const std::string reference_text = "reference: " + reference.meta.integrator + ", " +
                                     std::to_string(reference.meta.spp) + " spp";
  const ContactSheet sheet = contact_sheet(reference, reference_text, sheet_renders);
  write_labelled_preview(sheet.image, sheet.labels, font, sheet_file);
  report["contact_sheet"] = {{"file", sheet_file.string()},
                             {"labels", font.has_value()},
                             {"font", font ? font->string() : ""},
                             {"zoom", sheet.zoom}};
  write_json_file(report, (dir / "compare.json").string());
  std::printf("wrote %s\nwrote %s\n", sheet_file.c_str(), (dir / "compare.json").c_str());
  return 0;
}

}  // namespace snee
