// The machine-readable record of one render (`snee render --stats FILE`), read by benchmark
// scripts and tests; docs in README.md ("Statistics").
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "scheduler/render.h"

namespace snee {

// Rays traced by kind (camera, extension, shadow, probe) and their total.
nlohmann::ordered_json ray_counts_json(const RenderStats& stats);

// Seconds in each stage, summed over threads.
nlohmann::ordered_json stage_seconds_json(const RenderStats& stats);

// SIMD width and lane occupancy, overall and per batched stage kernel.
nlohmann::ordered_json simd_lanes_json(const RenderStats& stats);

// With `tile_seconds`, also RenderStats::tile_seconds; a split render's processes are listed
// whenever there are several.
nlohmann::ordered_json stats_json(const std::string& scene, const RenderOptions& options,
                                  const RenderResult& result, bool tile_seconds = false);
// The SNEE options as `--stats` and the EXR's snee:render_options write them.
nlohmann::ordered_json snee_options_json(const SneeOptions& snee);

// Non-finite samples count as 0 in the image, which darkens it without a trace: the warning
// a render prints at its end ("warning: 3 of 1024 samples (0.293%) were not finite ..."), or
// "" when every sample was finite.
std::string nonfinite_warning(const RenderStats& stats);
// The warning for a medium whose mean free path is too short for float precision at the scene's
// size (shortest_free_path, scheduler/render.h), or "". Given before rendering.
std::string dense_medium_warning(const ShortestFreePath& shortest);

// `snee` renders as `pt` when every light looks larger than --snee-light-limit: the note it
// prints then ("note: snee ran as pt: ..."), or "" when SNEE ran or another integrator did.
std::string snee_engagement_note(const RenderOptions& options, const RenderStats& stats);
// For "snee" with grid media in the scene, the note that says they are sampled as pt samples
// them ("note: snee samples the grid media 'smoke' as pt does: ..."), or "".
std::string grid_media_note(const RenderOptions& options, const Scene& scene);

// Throws std::runtime_error naming the file if it cannot be written.
void write_json_file(const nlohmann::ordered_json& json, const std::string& path);

}  // namespace snee
