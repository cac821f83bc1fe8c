#include "apps/thread_counts.h"

#include <charconv>

namespace snee {

std::optional<std::vector<int>> parse_thread_counts(const std::string& text) {
  std::vector<int> counts;
  size_t begin = 0;
  while (begin <= text.size()) {
    const size_t end = std::min(text.find(',', begin), text.size());
    int value = 0;
    const auto [ptr, ec] = std::from_chars(text.data() + begin, text.data() + end, value);
    if (ec != std::errc() || ptr != text.data() + end || value < 1 || value > 1024)
      return std::nullopt;
    counts.push_back(value);
    begin = end + 1;
  }
  return counts;
}

CLI::Validator thread_counts_validator() {
  return CLI::Validator(
      [](const std::string& text) {
        return parse_thread_counts(text)
                   ? std::string()
                   : "expected positive integers like 1,2, got '" + text + "'";
      },
      "LIST");
}

}  // namespace snee
