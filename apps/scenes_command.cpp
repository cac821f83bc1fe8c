#include "apps/scenes_command.h"

#include <algorithm>
#include <cstdio>

#include "scene/scene_loader.h"

namespace snee {

ScenesCommand::ScenesCommand(CLI::App& parent)
    : command_(parent.add_subcommand(
          "scenes", "List the built-in scenes (render one with `snee render builtin:NAME`)")) {}

int ScenesCommand::run() const {
  const auto scenes = builtin_scenes();
  size_t width = 0;
  for (const auto& s : scenes) width = std::max(width, s.name.size());
  for (const auto& s : scenes)
    std::printf("%-*s  %s\n", static_cast<int>(width), s.name.c_str(), s.description.c_str());
  return 0;
}

}  // namespace snee
