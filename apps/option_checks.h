// Checks of numeric command-line options shared by every subcommand. CLI11's own range checks
// let NaN through (every comparison with it is false) and print their bounds as doubles with
// hundreds of digits; these accept only finite values in range and name the bounds plainly.
#pragma once

#include <charconv>
#include <limits>
#include <string>

#include <CLI/CLI.hpp>

namespace snee {

template <typename Int>
CLI::Validator integer_in_range(Int min, Int max) {
  const std::string expected =
      "an integer from " + std::to_string(min) + " to " + std::to_string(max);
  return CLI::Validator(
      [min, max, expected](const std::string& text) {
        Int value{};
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        return ec == std::errc() && end == text.data() + text.size() && value >= min && value <= max
                   ? std::string()
                   : "expected " + expected + ", got '" + text + "'";
      },
      min > 0 ? "POSITIVE" : "NONNEGATIVE");
}

template <typename Int>
CLI::Validator integer_at_least(Int min) {
  return integer_in_range(min, std::numeric_limits<Int>::max());
}

// A finite number in [min, max].
CLI::Validator finite_in_range(double min, double max);
// A finite number >= min.
CLI::Validator finite_at_least(double min);
// A finite number > 0.
CLI::Validator finite_positive();

// `requested` worker threads, or max_render_threads() (scheduler/render.h) with a warning on
// stderr naming `option` when it asks for more. 0 (all hardware threads) stays 0.
int capped_threads(int requested, const char* option = "--threads");

}  // namespace snee
