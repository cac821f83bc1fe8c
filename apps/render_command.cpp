#include "apps/render_command.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>

#include "apps/checkpoint_file.h"
#include "apps/interrupt_request.h"
#include "apps/option_checks.h"
#include "apps/output_files.h"
#include "apps/progress_bar.h"
#include "apps/render_settings.h"
#include "apps/resolution.h"
#include "apps/sample_counts.h"
#include "apps/simd_option.h"
#include "apps/stats_json.h"
#include "kernels/physics/snee/manifold_mesh_chains.h"
#include "scene/aov_selection.h"
#include "scene/scene_loader.h"
#include "scene/shape_bounds.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

std::string output_name(const Scene& scene, const std::string& spec) {
  if (!scene.name.empty() && scene.name.find_first_of("/\\") == std::string::npos)
    return scene.name;
  const std::string builtin = "builtin:";
  if (spec.starts_with(builtin)) return spec.substr(builtin.size());
  return fs::path(spec).stem().string();
}

// "64 spp", or what the budgets left of it: "24 of 1000 spp (time budget spent)", "mean 37.5
// spp, 16 to 256 (noise target 0.05)".
std::string samples_summary(const RenderResult& result, int spp) {
  const Film& film = result.film;
  char text[160];
  if (film.meta.noise_target > 0 && !film.pixel_spp.empty()) {
    const SampleCounts counts = sample_counts(film);
    std::snprintf(text, sizeof text, "mean %.1f spp, %d to %u of %d (noise target %g%s)",
                  counts.mean, film.meta.min_spp, counts.most, spp, film.meta.noise_target,
                  result.time_budget_spent ? ", time budget spent" : "");
  } else if (result.time_budget_spent) {
    std::snprintf(text, sizeof text, "%d of %d spp (time budget spent)", film.meta.min_spp, spp);
  } else {
    std::snprintf(text, sizeof text, "%d spp", spp);
  }
  return text;
}

}  // namespace

RenderCommand::RenderCommand(CLI::App& parent)
    : command_(parent.add_subcommand("render", "Render a scene to an EXR and a PNG preview")) {
  CLI::App& c = *command_;
  c.add_option("SCENE", scene_,
               "JSON scene file, or builtin:NAME for a built-in scene (see `snee scenes`)")
      ->capture_default_str();
  c.add_option("--spp", options_.spp, "Samples per pixel [default: the scene's, else 64]")
      ->check(integer_at_least(1));
  c.add_option("--threads", options_.threads,
               "Worker threads, 0 = all hardware threads; at most " +
                   std::to_string(kMaxThreadsPerHardwareThread) + " per hardware thread")
      ->check(integer_at_least(0))
      ->capture_default_str();
  c.add_option("--seed", options_.seed, "Random seed [default: the scene's, else 0]")
      ->check(integer_at_least(uint32_t{0}));
  c.add_option("--integrator", options_.integrator,
               "pt (path tracing), snee (pt + subdivision NEE) or sla (straight-line shadow rays: "
               "biased, for comparison) [default: the scene's, else pt]")
      ->check(CLI::IsMember({"pt", "snee", "sla"}));
  c.add_option("-o,--output", output_,
               "Output image: FILE.exr gets its preview FILE.png beside it; FILE.png, .jpg, "
               ".jpeg (tone-mapped 8-bit preview) or .hdr (linear radiance) gets FILE.exr, "
               "which alone keeps the variance and the settings, beside it")
      ->default_str("out/<scene-name>.exr")
      ->check([](const std::string& path) {
        return is_output_extension(fs::path(path).extension())
                   ? std::string()
                   : std::string("the output must end in ") + kOutputExtensions + ": " + path;
      });
  add_simd_option(c, options_.simd);
  c.add_option("--stats", stats_, "Also write render statistics as JSON to this file");
  c.add_flag("--stats-tiles", stats_tiles_,
             "With --stats: also each tile's seconds of thread time (tile_seconds, raster order), "
             "the cost map load-balance studies start from (docs/performance.md)");
  c.add_option("--resolution", resolution_,
               "Image size WxH, overriding the camera's (keeps its field of view along fov_axis)")
      ->check(resolution_validator());
  c.add_option("--max-depth", options_.max_depth,
               "Maximum scattering events per path [default: the scene's, else 1024]")
      ->check(integer_at_least(0));
  c.add_option("--queue-capacity", options_.queue_capacity,
               "Path slots per work unit (batch size of every stage)")
      ->check(integer_in_range(kMinQueueCapacity, kMaxQueueCapacity))
      ->capture_default_str();
  c.add_option("--tile-size", options_.tile_size, "Work-unit tile edge in pixels")
      ->check(integer_in_range(1, kMaxTileSize))
      ->capture_default_str();
  c.add_option("--samples-per-unit", options_.samples_per_unit,
               "Sample indices per pixel in one work unit (a tile times this many samples)")
      ->check(integer_in_range(1, kMaxSamplesPerUnit))
      ->capture_default_str();
  c.add_option("--schedule", options_.schedule,
               "megakernel (one path at a time, the comparison twin), local (wavefront per work "
               "unit) or global (each stage over many units)")
      ->check(CLI::IsMember({"megakernel", "local", "global"}))
      ->capture_default_str();
  c.add_option(
       "--checkpoint", checkpoint_seconds_,
       "Also write the image so far, and the render's state beside it (FILE.exr.checkpoint, "
       "which --resume goes on from), every SECONDS while rendering (0: only at the end); "
       "split across processes, each writes its state only")
      ->check(finite_at_least(0))
      ->capture_default_str();
  c.add_option("--resume", resume_,
               "Go on with the render whose EXR is FILE from the state beside it "
               "(FILE.checkpoint): same scene and options, any thread count; the image is "
               "bitwise the uninterrupted render's. -o defaults to FILE (docs/resume.md)");
  c.add_option("--time", options_.time_seconds,
               "Stop after about SECONDS: once they have passed no new round (--samples-per-unit "
               "samples of every pixel) starts, so every pixel holds whole rounds "
               "(docs/budgets.md)")
      ->check(finite_positive());
  c.add_option("--noise-target", options_.noise_target,
               "Adaptive sampling: each tile takes rounds until every pixel's relative standard "
               "error of luminance is at most REL, up to --spp; 0 turns off a target the scene "
               "sets in render.noise_target (docs/budgets.md)")
      ->check(finite_at_least(0));
  c.add_option("--light-selection", light_selection_,
               "How a light sample picks its light: uniform, or power (in proportion to each "
               "light's estimated power, docs/lights.md) [default: the scene's "
               "render.light_selection, else uniform]")
      ->check(CLI::IsMember({"uniform", "power"}));
  c.add_flag("-q,--quiet", quiet_, "No progress output while rendering");
  c.add_option_function<std::string>(
       "--max-memory",
       [this](const std::string& text) { options_.memory_budget.bytes = *parse_byte_size(text); },
       "Most memory one large allocation may take: the scene file, a mesh's arrays, an "
       "environment image, the film with its work buffers (e.g. 512M, 4G; K, M, G, T are powers "
       "of 1024) [default: the physical memory, " +
           format_bytes(options_.memory_budget.bytes) + "]")
      ->check(CLI::Validator(
          [](const std::string& text) {
            return parse_byte_size(text)
                       ? std::string()
                       : "expected a size such as 4G, 512M or 1000000, got '" + text + "'";
          },
          "SIZE"));
  add_image_options(c);

  const std::string snee = "SNEE (docs/snee-implementation.md)";
  c.add_option("--snee-probe", snee_probe_,
               "Direction of the exit-point probe: uniform (sphere), phase (HG at x_i) or "
               "lights (mostly toward the small lights)")
      ->check(CLI::IsMember({"uniform", "phase", "lights"}))
      ->capture_default_str()
      ->group(snee);
  c.add_option("--snee-distance-mix", options_.snee.c_exponential,
               "Probability that top-to-bottom draws the distance by free flight rather than "
               "equiangularly")
      ->check(finite_in_range(0, 1))
      ->capture_default_str()
      ->group(snee);
  c.add_option("--snee-joint-mix", options_.snee.c_joint,
               "Probability that bottom-to-top draws the direction from the geometric "
               "joint-importance lobe rather than the phase function (g != 0 only)")
      ->check(finite_in_range(0, 1))
      ->capture_default_str()
      ->group(snee);
  c.add_option("--snee-heuristic", snee_heuristic_, "Multi-sample MIS heuristic: balance or power")
      ->check(CLI::IsMember({"balance", "power"}))
      ->capture_default_str()
      ->group(snee);
  c.add_option("--snee-light-limit", options_.snee.light_limit_degrees,
               "SNEE runs only when some light fills a cone of at most this half-angle in "
               "degrees as seen from the objects (delta lights 0, environments 180); otherwise "
               "snee renders as pt. 180: always SNEE")
      ->check(finite_in_range(0, 180))
      ->capture_default_str()
      ->group(snee);
  c.add_option("--snee-chains", snee_chains_,
               "Whether the manifold strategy follows the light through internal reflections "
               "inside a smooth sphere or closed flat-shaded mesh (on, the default; off leaves "
               "those paths out, to measure them, and builds no chain trees: docs/method.md 3.12, "
               "3.14)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str()
      ->group(snee);
  c.add_option("--snee-chain-levels", options_.snee.mesh_chain_levels,
               "Most reflections and crossings of the chains behind a closed flat-shaded mesh "
               "under a directional light (1 to " +
                   std::to_string(kMaxMeshChainLevels) +
                   "): each level holds about twice the fragments of the one below, in memory "
                   "and build time; longer chains are counted as manifold_chains_unsupported "
                   "(docs/method.md 3.14)")
      ->check(CLI::Range(1, kMaxMeshChainLevels))
      ->capture_default_str()
      ->group(snee);
  c.add_option("--snee-probe-rate", options_.snee.probe_rate,
               "Probability that a medium vertex runs the exit-point probe and with it "
               "top-to-bottom and bottom-to-top (docs/method.md 3.2); 1 runs them everywhere")
      ->check(finite_positive())
      ->check(finite_in_range(0, 1))
      ->capture_default_str()
      ->group(snee);
  c.add_option("--snee-manifold-rate", options_.snee.manifold_rate,
               "Probability that the manifold strategy runs at a medium vertex below the first "
               "scattering, where top-to-bottom shares its paths (docs/method.md 3.10); 1 runs "
               "it everywhere")
      ->check(finite_positive())
      ->check(finite_in_range(0, 1))
      ->capture_default_str()
      ->group(snee);
  c.add_option("--snee-guide-rate", options_.snee.guide_rate,
               "Probability that the guided exit runs at a medium vertex whose parent is a "
               "surface vertex, inside a sphere or closed flat-shaded mesh boundary: it draws the "
               "direction toward where "
               "the boundary refracts a small light (docs/method.md 3.15); 0 turns it off")
      ->check(finite_in_range(0, 1))
      ->capture_default_str()
      ->group(snee);
  c.add_option("--snee-guide-cap", options_.snee.guide_cap_degrees,
               "Half-angle in degrees of the cone the guided exit draws its direction in")
      ->check(finite_positive())
      ->check(finite_in_range(0, 90))
      ->capture_default_str()
      ->group(snee);
  c.add_option("--snee-strategies", snee_strategies_,
               "Comma-separated strategies that share the transport SNEE handles: tb "
               "(top-to-bottom), bt (bottom-to-top), ub (BSDF-sampled exit), ul (light-sampled "
               "exit), mn (refracted next-event estimation through a smooth sphere or flat-shaded "
               "mesh); a subset "
               "isolates them")
      ->check(CLI::Validator(
          [](const std::string& text) {
            try {
              parse_strategy_set(text);
              return std::string();
            } catch (const std::invalid_argument& e) {
              return std::string(e.what());
            }
          },
          "LIST"))
      ->capture_default_str()
      ->group(snee);
}

void RenderCommand::add_image_options(CLI::App& c) {
  const std::string group = "Output images (docs/output-images.md)";
  c.add_option("--exposure", exposure_ev_,
               "Preview exposure in stops: each +1 doubles the radiance before the tone curve "
               "(PNG/JPEG only; the EXR and .hdr stay linear)")
      ->check(finite_in_range(-64, 64))
      ->capture_default_str()
      ->group(group);
  c.add_option("--tone-curve", tone_curve_,
               "Preview tone curve: filmic (ACES fit, highlights roll off) or clamp (clip at 1)")
      ->check(CLI::IsMember({"filmic", "clamp"}))
      ->capture_default_str()
      ->group(group);
  c.add_option("--clamp", options_.sample_clamp,
               "BIASED: clip each sample's RGB radiance to VALUE before averaging (removes "
               "fireflies and energy with them; recorded as snee:sample_clamp in the EXR) "
               "[default: off]")
      ->check(finite_positive())
      ->group(group);
  c.add_option_function<std::string>(
       "--aov", [this](const std::string& text) { options_.aovs = parse_aov_list(text); },
       "Denoiser layers in the EXR, a comma-separated list of albedo (albedo.R/G/B), normal "
       "(N.X/Y/Z, world space) and depth (Z): those of the first non-specular hit, seen through "
       "smooth dielectrics; the beauty image stays the same [default: none]")
      ->check(CLI::Validator(
          [](const std::string& text) {
            try {
              parse_aov_list(text);
              return std::string();
            } catch (const std::invalid_argument& e) {
              return std::string(e.what());
            }
          },
          "LIST"))
      ->group(group);
}

ToneMap RenderCommand::preview_tone() const {
  return {exposure_ev_, tone_curve_ == "clamp" ? ToneCurve::kClamp : ToneCurve::kFilmic};
}

int RenderCommand::run(const RenderDistribution& distribution) const {
  LoadedScene loaded = load_scene(scene_, options_.memory_budget);
  for (const std::string& warning : loaded.warnings)
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
  const std::string dense =
      dense_medium_warning(shortest_free_path(loaded.scene, ray_clearance(loaded.scene)));
  if (!dense.empty()) std::fprintf(stderr, "%s\n", dense.c_str());
  Scene& scene = loaded.scene;

  RenderOptions options = options_;
  options.snee.probe = probe_directions_named(snee_probe_);
  options.snee.heuristic =
      snee_heuristic_ == "power" ? MisHeuristic::kPower : MisHeuristic::kBalance;
  options.snee.enabled = parse_strategy_set(snee_strategies_);
  options.snee.reflection_chains = snee_chains_ == "on";
  options.threads = capped_threads(options.threads);
  const bool claims_tiles = static_cast<bool>(distribution.tile_source);
  if (!claims_tiles) {
    options.shard = distribution.shard;
    options.shard_count = distribution.shard_count;
  }
  // A state holds a fixed set of tiles, and which tiles a process claims is known only at the end.
  if (claims_tiles && (checkpoint_seconds_ > 0 || !resume_.empty()))
    throw std::invalid_argument(
        "--checkpoint and --resume need the static split (--split static): with tiles claimed "
        "while rendering, no process knows its tiles in advance");
  // Each process would read its own clock and stop at its own round.
  if (distribution.shard_count > 1 && options.time_seconds > 0)
    throw std::invalid_argument(
        "--time is not available when the render is split across processes");
  // The saved state holds the radiance sums only: resumed layers would average part of the
  // samples over all of them.
  if (!resume_.empty() && options.aovs.any())
    throw std::invalid_argument(
        "--aov is not available with --resume: the checkpoint state holds no AOV layers "
        "(docs/resume.md)");
  const bool shows_progress = !quiet_ && distribution.shard == 0;
  if (!given("--spp")) options.spp = scene.render.spp;
  if (!given("--max-depth")) options.max_depth = scene.render.max_depth;
  if (!given("--seed")) options.seed = scene.render.seed;
  if (!given("--integrator")) options.integrator = scene.render.integrator;
  if (!given("--noise-target")) options.noise_target = scene.render.noise_target;
  options.light_selection = light_selection_.empty() ? scene.render.light_selection
                                                     : *parse_light_selection(light_selection_);
  if (const auto size = parse_resolution(resolution_)) {
    // The field of view is kept along the camera's fov_axis; the other edge follows the new
    // aspect ratio.
    scene.camera.width = size->width;
    scene.camera.height = size->height;
  }

  const std::string name = output_name(scene, scene_);
  scene.name = name;  // render() stamps it on the film and on every checkpoint
  // A resumed render goes on writing the files it continues, unless told otherwise.
  const fs::path output = !output_.empty()   ? fs::path(output_)
                          : !resume_.empty() ? fs::path(resume_)
                                             : fs::path("out") / (name + ".exr");
  OutputImages images = output_images(output);
  images.tone = preview_tone();
  images.attributes = render_settings_attributes(scene_, loaded, options, images.tone);
  const fs::path& exr = images.exr;
  const fs::path& png = images.view;
  // Only the process that writes checks, before any sampling, so a bad destination costs
  // nothing; each check leaves the directory it needs in place.
  const bool writes = distribution.shard == 0;
  const CheckpointIdentity identity = checkpoint_identity(scene_, loaded, options);
  std::optional<FilmState> resumed;
  if (!resume_.empty()) {
    resumed = read_checkpoint(
        checkpoint_path(resume_, distribution.shard, distribution.shard_count), identity);
  }
  const fs::path state_file = checkpoint_path(exr, distribution.shard, distribution.shard_count);
  if (writes) {
    const int w = scene.camera.width, h = scene.camera.height;
    check_destination(exr, exr_bytes_bound(w, h) + view_bytes_bound(w, h));
    check_destination(png, 0);
    if (!stats_.empty()) check_destination(stats_, 0);
  }
  // The images are what was asked for; the state (a longer name beside the EXR) only makes a
  // stop resumable, so a render that cannot keep it still runs, warned.
  try {
    if (!claims_tiles)
      check_destination(state_file,
                        checkpoint_bytes_bound(scene.camera.width, scene.camera.height));
  } catch (const std::exception& e) {
    std::fprintf(stderr,
                 "warning: the render's state cannot be kept, a stop cannot be resumed: %s\n",
                 e.what());
  }

  ProgressBar bar(stderr, {}, options.time_seconds);
  RenderHooks hooks;
  if (shows_progress) hooks.progress = [&bar](const Progress& p) { bar.update(p); };
  // A failed checkpoint (disk full, directory removed) loses no samples: the render goes
  // on and the next checkpoint tries again; only the final write decides the exit code.
  const auto checkpoint_or_warn = [](const std::function<void()>& write) {
    try {
      write();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "warning: checkpoint not written, rendering goes on: %s\n", e.what());
    }
  };
  hooks.checkpoint_seconds = checkpoint_seconds_;
  // One process of a split render holds only its shard's pixels: it keeps its state alone.
  if (checkpoint_seconds_ > 0 && distribution.shard_count == 1) {
    hooks.checkpoint = [&](const Film& film) {
      checkpoint_or_warn([&] { write_images(film, images); });
    };
  }
  // Also set without --checkpoint: a stopped render keeps its final state (RenderResult).
  if (!claims_tiles) {
    hooks.checkpoint_state = [&](const FilmState& state) {
      checkpoint_or_warn([&] { write_checkpoint(state_file, identity, state); });
    };
  }
  hooks.tile_source = distribution.tile_source;
  const InterruptRequest interrupt;
  hooks.stop_requested = [&] {
    const bool here = interrupt.requested();
    const bool elsewhere =
        distribution.stop_together && distribution.stop_together(interrupt.exit_status());
    return here || elsewhere;
  };
  RenderResult result;
  try {
    result = render(scene, options, hooks, resumed ? &*resumed : nullptr);
  } catch (const std::invalid_argument& e) {
    bar.finish();
    throw std::invalid_argument("cannot render '" + name + "' with integrator '" +
                                options.integrator + "': " + e.what());
  }
  bar.finish();
  // An image cut short without a signal here was cut short elsewhere (or failed): never 0.
  int exit_status = result.complete ? 0 : std::max(1, interrupt.exit_status());
  // Every process keeps its own state, before the join. A complete render keeps it only when
  // asked to checkpoint or resumed (so that it can be taken further, to a larger spp); else a
  // state left by an earlier stopped render of this EXR is gone with the EXR it belonged to.
  if (!claims_tiles && (!result.complete || checkpoint_seconds_ > 0 || resumed)) {
    try {
      write_checkpoint(state_file, identity, *result.state);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "warning: the render's state was not kept, it cannot be resumed: %s\n",
                   e.what());
    }
  } else {
    if (!result.complete)
      std::fprintf(stderr,
                   "warning: processes that claim tiles while rendering keep no state, this stop "
                   "cannot be resumed (--split static, or --checkpoint, keeps one)\n");
    std::error_code ignored;
    fs::remove(state_file, ignored);
  }
  if (distribution.join && !distribution.join(result, exit_status)) return exit_status;

  const std::string nonfinite = nonfinite_warning(result.stats);
  if (!nonfinite.empty()) std::fprintf(stderr, "%s\n", nonfinite.c_str());
  const std::string engagement = snee_engagement_note(options, result.stats);
  if (!engagement.empty()) std::fprintf(stderr, "%s\n", engagement.c_str());
  const std::string grids = grid_media_note(options, loaded.scene);
  if (!grids.empty()) std::fprintf(stderr, "%s\n", grids.c_str());
  write_images(result.film, images);
  if (!stats_.empty()) write_json_file(stats_json(name, options, result, stats_tiles_), stats_);
  if (result.complete) {
    std::printf("rendered %s: %s, %dx%d, %s, %.2f s, %.1f Mrays/s, %s\n", name.c_str(),
                options.integrator.c_str(), result.film.width, result.film.height,
                samples_summary(result, options.spp).c_str(), result.stats.seconds,
                result.stats.mrays_per_second(),
                std::string(simd_level_name(result.stats.simd_level)).c_str());
  } else {
    std::printf(
        "interrupted %s after %llu of %lld pixel samples (every pixel has at least %d "
        "of %d spp)\n",
        name.c_str(), static_cast<unsigned long long>(result.stats.paths),
        static_cast<long long>(result.film.width) * result.film.height * options.spp,
        result.film.meta.min_spp, options.spp);
  }
  std::printf("wrote %s\nwrote %s\n", exr.c_str(), png.c_str());
  if (!stats_.empty()) std::printf("wrote %s\n", stats_.c_str());
  return exit_status;
}

}  // namespace snee
