// Parsing `--threads 1,2,4`: the thread counts a benchmark or scaling study runs at.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace snee {

// "1,2,4" -> {1, 2, 4}; nullopt unless every entry is a positive integer (at most 1024).
std::optional<std::vector<int>> parse_thread_counts(const std::string& text);
// The check of `--threads LIST`.
CLI::Validator thread_counts_validator();

}  // namespace snee
