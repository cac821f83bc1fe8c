// The checkpoint file of a render: the film's exact state (scheduler/film_state.h) written
// beside the EXR as FILE.exr.checkpoint (FILE.exr.checkpoint.R-of-N for process R of a render
// split across N), with what made it, so that `snee render --resume FILE.exr` goes on from it
// and refuses a state that another render left (docs/resume.md).
#pragma once

#include <cstdint>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "scene/scene_loader.h"
#include "scheduler/film_state.h"
#include "scheduler/render.h"

namespace snee {

// Where the state of `exr`'s render is kept by process `shard` of `shard_count`.
std::filesystem::path checkpoint_path(const std::filesystem::path& exr, int shard, int shard_count);

// Upper bound of the file's size for a width x height image.
uintmax_t checkpoint_bytes_bound(int width, int height);

// Everything a resumed render must share with the one that wrote the state for the samples to
// be the same ones, besides spp: snee's version, the scene's digest, the integrator and its
// options, seed, depth, resolution, tile and unit size, noise target, clamp and the process's
// share. The thread count, schedule and queue capacity are not in it: they never change the
// image.
struct CheckpointIdentity {
  nlohmann::ordered_json fields;  // name -> value, compared one by one
  int spp = 0;
  int samples_per_unit = 0;
};
CheckpointIdentity checkpoint_identity(const std::string& scene_spec, const LoadedScene& loaded,
                                       const RenderOptions& options);

// Writes `state` to `file` whole (output_files.h, replace_file). Throws std::runtime_error.
void write_checkpoint(const std::filesystem::path& file, const CheckpointIdentity& identity,
                      const FilmState& state);

// Reads the state in `file` for a render of `identity`. Throws std::runtime_error naming the
// file and what is wrong: missing, not a checkpoint, corrupt or truncated, made by a render
// whose identity differs (each differing setting with both values), or an spp the state cannot
// go on to (a larger spp only when the state's last chunk was whole).
FilmState read_checkpoint(const std::filesystem::path& file, const CheckpointIdentity& identity);

}  // namespace snee
