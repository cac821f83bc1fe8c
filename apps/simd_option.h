// --simd: the SIMD level whose kernels render (scheduler/simd_dispatch.h), for every command
// that renders; and the --version text that says which levels this machine can use.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "kernels/simd/simd_level.h"

namespace snee {

// Adds --simd LEVEL to a command. A level this machine cannot use is a usage error naming why
// and the levels it can.
CLI::Option* add_simd_option(CLI::App& command, std::optional<SimdLevel>& level);

// The levels of a comma-separated list of names, or every usable level for "all"; an unknown or
// unusable level throws std::invalid_argument naming it and why.
std::vector<SimdLevel> parse_simd_levels(const std::string& list);

// The level a render with this option and schedule uses, and why, for messages and metadata:
// "avx512 (16 float lanes), the widest this machine runs", "sse4.2 (4 float lanes), the
// megakernel's default" or "avx2 (8 float lanes), forced by --simd".
std::string simd_choice_text(const std::optional<SimdLevel>& level, const std::string& schedule);

// "snee 0.1.0", then the chosen level and each level's standing.
std::string version_text();

}  // namespace snee
