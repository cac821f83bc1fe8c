// Reading scenes: JSON files (docs/scene-format.md), built-in scenes by name, and writing a
// scene back to JSON. Every error is a SceneError whose message names the file, the JSON path
// (e.g. "shapes[2].medium.sigma_s[1]") or line, and what was expected.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/memory_budget.h"
#include "scene/scene.h"
#include "scene/scene_error.h"

namespace snee {

struct LoadedScene {
  Scene scene;
  std::vector<std::string> warnings;  // e.g. an open mesh given an interior medium
  // The document that was read with every default filled in, inline materials and media moved
  // to the named lists, transforms collapsed to one matrix and file paths made absolute (paths
  // under data/ stay relative to SNEE_DATA_DIR). Loading it again gives the same scene.
  nlohmann::json canonical;
};

// "builtin:NAME" loads a built-in scene; anything else is a path to a JSON scene file. Every
// file read (the scene file, meshes, images) must be a regular file, and it and the arrays made
// from it must each fit in `budget` (memory_budget.h).
LoadedScene load_scene(const std::string& spec, const MemoryBudget& budget = {});
LoadedScene load_scene_file(const std::string& path, const MemoryBudget& budget = {});
// Parses an already-read document; `origin` names it in messages and `base_dir` resolves
// relative mesh and image paths.
LoadedScene load_scene_json(const nlohmann::json& doc, const std::string& origin,
                            const std::string& base_dir, const MemoryBudget& budget = {});

struct BuiltinSceneInfo {
  std::string name;
  std::string description;
};
std::vector<BuiltinSceneInfo> builtin_scenes();
LoadedScene load_builtin_scene(const std::string& name);  // SceneError for unknown names

}  // namespace snee
