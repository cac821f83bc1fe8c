#include "apps/error_command.h"

#include <cstdio>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/image_error.h"
#include "apps/sample_counts.h"
#include "apps/stats_json.h"
#include "scene/film.h"

namespace snee {
namespace {

nlohmann::ordered_json samples_json(const Film& film) {
  const SampleCounts counts = sample_counts(film);
  return {{"requested", film.meta.spp},
          {"mean", counts.mean},
          {"min", counts.fewest},
          {"max", counts.most}};
}

nlohmann::ordered_json image_json(const std::string& file, const Film& film) {
  return {{"file", file},
          {"scene", film.meta.scene},
          {"integrator", film.meta.integrator},
          {"seed", film.meta.seed},
          {"noise_target", film.meta.noise_target},
          {"spp", samples_json(film)}};
}

}  // namespace

ErrorCommand::ErrorCommand(CLI::App& parent)
    : command_(parent.add_subcommand(
          "error",
          "Relative MSE of a render against a reference EXR of the same size, and the render's "
          "samples per pixel")) {
  CLI::App& c = *command_;
  c.add_option("RENDER", render_, "The render's EXR")->required();
  c.add_option("REFERENCE", reference_,
               "The reference's EXR (its variance channels, when present, measure its own noise)")
      ->required();
  c.add_option("--json", json_, "Also write the figures as JSON to this file");
}

int ErrorCommand::run() const {
  const Film render = read_exr(render_);
  const Film reference = read_exr(reference_);
  ImageError error;
  try {
    error = image_error(render, reference);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(render_ + " against " + reference_ + ": " + e.what());
  }
  if (reference.variance_of_mean.empty()) {
    std::fprintf(stderr,
                 "warning: %s has no variance channels, so its own noise is not subtracted: "
                 "the relative MSE is the raw one\n",
                 reference_.c_str());
  }
  const SampleCounts render_spp = sample_counts(render);
  const SampleCounts reference_spp = sample_counts(reference);
  std::printf("render      %s: %dx%d, mean %.2f spp (%u to %u)\n", render_.c_str(), render.width,
              render.height, render_spp.mean, render_spp.fewest, render_spp.most);
  std::printf("reference   %s: mean %.2f spp (%u to %u)\n", reference_.c_str(), reference_spp.mean,
              reference_spp.fewest, reference_spp.most);
  std::printf("relMSE      %.6e (the reference's noise subtracted)\n", error.relative_mse);
  std::printf("raw         %.6e\n", error.relative_mse_raw);
  std::printf("trimmed     %.6e (without the worst %g%% of pixels)\n", error.relative_mse_trimmed,
              100 * kTrimmedFraction);
  std::printf("ref. noise  %.6e\n", error.reference_noise);
  if (!json_.empty()) {
    const nlohmann::ordered_json report = {{"render", image_json(render_, render)},
                                           {"reference", image_json(reference_, reference)},
                                           {"resolution", {render.width, render.height}},
                                           {"relative_mse_floor", kRelativeMseFloor},
                                           {"relative_mse", error.relative_mse},
                                           {"relative_mse_raw", error.relative_mse_raw},
                                           {"relative_mse_trimmed", error.relative_mse_trimmed},
                                           {"trimmed_fraction", kTrimmedFraction},
                                           {"reference_noise", error.reference_noise}};
    write_json_file(report, json_);
  }
  return 0;
}

}  // namespace snee
