// The snee command line: parses arguments, dispatches to one subcommand and turns every error
// into a message and an exit code (1 = failure, 2 = bad scene, CLI11's codes for bad usage).
#include <string>

#include <CLI/CLI.hpp>

#include "apps/bench_command.h"
#include "apps/compare_command.h"
#include "apps/error_command.h"
#include "apps/error_exit.h"
#include "apps/render_command.h"
#include "apps/scale_command.h"
#include "apps/scenes_command.h"
#include "apps/simd_option.h"

int main(int argc, char** argv) {
  CLI::App app("snee: a CPU renderer for translucent objects", "snee");
  app.set_version_flag("--version", snee::version_text);
  app.require_subcommand(1);
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "error: " + std::string(e.what()) + "\nrun 'snee --help' or 'snee COMMAND --help'\n";
  });
  const snee::RenderCommand render(app);
  const snee::ScenesCommand scenes(app);
  const snee::BenchCommand bench(app);
  const snee::ScaleCommand scale(app);
  const snee::CompareCommand compare(app);
  const snee::ErrorCommand error(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return snee::run_reporting_errors([&] {
    if (bench.selected()) return bench.run();
    if (scale.selected()) return scale.run();
    if (compare.selected()) return compare.run();
    if (error.selected()) return error.run();
    return render.selected() ? render.run() : scenes.run();
  });
}
