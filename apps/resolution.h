// Parsing `--resolution WxH`.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace snee {

struct Resolution {
  int width = 0;
  int height = 0;
};

// "640x480" -> {640, 480}; nullopt for anything else, including sizes outside
// [1, kMaxImageEdge] (scene/scene.h), the scenes' limit too.
std::optional<Resolution> parse_resolution(const std::string& text);
// The check of every command's `--resolution` option.
CLI::Validator resolution_validator();

}  // namespace snee
