// `snee render`: loads a scene, renders it with the scene's settings overridden by the command
// line, and writes the EXR with a view of it (a PNG preview, or the -o file's format) and
// optionally a statistics JSON. With
// --checkpoint it also writes the image so far while rendering; on Ctrl-C (SIGINT) or SIGTERM
// it stops, writes the image so far and exits with 128 + the signal number.
#pragma once

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

#include "scene/tone_map.h"
#include "scheduler/render.h"

namespace snee {

// How a render split across processes (apps/mpi/) shares the work: this process renders shard
// `shard` of `shard_count` (RenderOptions), or, with `tile_source`, the tiles it claims while
// it renders (RenderHooks::tile_source; then shard_count only says how many processes share
// the render). `stop_together` is asked while rendering with this
// process's exit status for a signal so far (0 if none, else 128 + its number), tells the
// others of one, and says whether any process has had one, so all stop together. `join`
// gathers every shard's result into one process's and turns `exit_status` (this process's)
// into the whole render's; it returns false on the processes that write nothing. The default
// is one process.
struct RenderDistribution {
  int shard = 0;
  int shard_count = 1;
  std::function<TileRange()> tile_source;
  std::function<bool(int exit_status)> stop_together;
  std::function<bool(RenderResult&, int& exit_status)> join;
};

class RenderCommand {
 public:
  // Registers the subcommand and its options on `parent`.
  explicit RenderCommand(CLI::App& parent);
  bool selected() const { return command_->parsed(); }
  // Returns the exit code; throws SceneError and other std::exceptions for main to report.
  int run(const RenderDistribution& distribution = {}) const;

 private:
  bool given(const std::string& option) const { return command_->count(option) > 0; }

  CLI::App* command_;
  std::string scene_ = "builtin:default";
  RenderOptions options_;
  std::string output_;
  std::string stats_;
  bool stats_tiles_ = false;  // tile_seconds in the --stats JSON
  std::string resolution_;
  double checkpoint_seconds_ = 0;
  std::string resume_;  // the EXR whose checkpoint state the render goes on from
  bool quiet_ = false;
  std::string light_selection_;  // empty: the scene's
  std::string snee_probe_ = "uniform";
  std::string snee_heuristic_ = "balance";
  std::string snee_strategies_ = "tb,bt,ub,ul,mn";
  std::string snee_chains_ = "on";
  // Output images (apps/output_files.h, docs/output-images.md).
  void add_image_options(CLI::App& c);
  ToneMap preview_tone() const;
  float exposure_ev_ = 0;
  std::string tone_curve_ = "filmic";
};

}  // namespace snee
