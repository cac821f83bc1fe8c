#include "apps/resolution.h"

#include <charconv>

#include "scene/scene.h"

namespace snee {
namespace {

bool parse_edge(const char* begin, const char* end, int& value) {
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  return ec == std::errc() && ptr == end && value > 0 && value <= kMaxImageEdge;
}

}  // namespace

std::optional<Resolution> parse_resolution(const std::string& text) {
  const size_t x = text.find('x');
  if (x == std::string::npos) return std::nullopt;
  Resolution r;
  const char* s = text.data();
  if (!parse_edge(s, s + x, r.width) || !parse_edge(s + x + 1, s + text.size(), r.height))
    return std::nullopt;
  return r;
}

CLI::Validator resolution_validator() {
  return CLI::Validator(
      [](const std::string& text) {
        return parse_resolution(text) ? std::string()
                                      : "expected WxH with sizes in [1, " +
                                            std::to_string(kMaxImageEdge) + "], got '" + text + "'";
      },
      "WxH");
}

}  // namespace snee
