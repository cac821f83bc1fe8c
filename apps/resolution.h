// Parsing `--resolution WxH`.
#pragma once

#include <optional>
#include <string>

namespace snee {

struct Resolution {
  int width = 0;
  int height = 0;
};

// "640x480" -> {640, 480}; nullopt for anything else, including zero or absurd sizes.
std::optional<Resolution> parse_resolution(const std::string& text);

}  // namespace snee
