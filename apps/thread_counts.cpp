#include "apps/thread_counts.h"

#include <charconv>

#include "apps/option_checks.h"

namespace snee {

std::optional<std::vector<int>> parse_thread_counts(const std::string& text) {
  std::vector<int> counts;
  size_t begin = 0;
  while (begin <= text.size()) {
    const size_t end = std::min(text.find(',', begin), text.size());
    int value = 0;
    const auto [ptr, ec] = std::from_chars(text.data() + begin, text.data() + end, value);
    if (ec != std::errc() || ptr != text.data() + end || value < 1) return std::nullopt;
    counts.push_back(value);
    begin = end + 1;
  }
  return counts;
}

std::vector<int> capped_thread_counts(const std::vector<int>& counts) {
  std::vector<int> capped;
  for (const int n : counts) capped.push_back(capped_threads(n));
  return capped;
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
