// Parsing `--threads 1,2,4`: the thread counts a benchmark or scaling study runs at.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace snee {

// "1,2,4" -> {1, 2, 4}; nullopt unless every entry is a positive integer.
std::optional<std::vector<int>> parse_thread_counts(const std::string& text);
// Each count capped at max_render_threads() (scheduler/render.h), with a warning for each
// one that was above it (option_checks.h, capped_threads).
std::vector<int> capped_thread_counts(const std::vector<int>& counts);
// The check of `--threads LIST`.
CLI::Validator thread_counts_validator();

}  // namespace snee
