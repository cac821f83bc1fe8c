#include "apps/simd_option.h"

#include <sstream>
#include <stdexcept>

#include "scheduler/simd_dispatch.h"

namespace snee {

CLI::Option* add_simd_option(CLI::App& command, std::optional<SimdLevel>& level) {
  return command
      .add_option_function<std::string>(
          "--simd", [&level](const std::string& name) { level = parse_simd_level(name); },
          "SIMD level of the kernels: sse4.2, avx2 or avx512; the image is bitwise the same at "
          "every level [default: the widest this machine runs, `snee --version` lists them]")
      ->check([](const std::string& name) -> std::string {
        const std::optional<SimdLevel> parsed = parse_simd_level(name);
        if (!parsed) return "the SIMD level must be sse4.2, avx2 or avx512: " + name;
        try {
          simd_backend(*parsed);
        } catch (const std::invalid_argument& e) {
          return e.what();
        }
        return {};
      });
}

std::vector<SimdLevel> parse_simd_levels(const std::string& list) {
  std::vector<SimdLevel> levels;
  if (list == "all") {
    for (const SimdLevelStatus& s : simd_levels())
      if (s.usable) levels.push_back(s.level);
    return levels;
  }
  std::stringstream names(list);
  std::string name;
  while (std::getline(names, name, ',')) {
    const std::optional<SimdLevel> level = parse_simd_level(name);
    if (!level)
      throw std::invalid_argument("--simd: a SIMD level is sse4.2, avx2 or avx512, not '" + name +
                                  "'");
    simd_backend(*level);  // throws if unusable, saying why
    levels.push_back(*level);
  }
  if (levels.empty()) throw std::invalid_argument("--simd names no SIMD level");
  return levels;
}

std::string simd_choice_text(const std::optional<SimdLevel>& level, const std::string& schedule) {
  if (level) return simd_level_description(*level) + ", forced by --simd";
  const SimdLevel chosen = default_simd_level(schedule);
  return simd_level_description(chosen) + (chosen == widest_simd_level()
                                               ? ", the widest this machine runs"
                                               : ", the megakernel's default");
}

std::string version_text() {
  std::string text =
      "snee " SNEE_VERSION "\nSIMD: " + simd_choice_text(std::nullopt, "local") +
      " (the megakernel's: " + std::string(simd_level_name(default_simd_level("megakernel"))) +
      ")\n";
  for (const SimdLevelStatus& s : simd_levels()) {
    const std::string name(simd_level_name(s.level));
    text += "  " + name + std::string(8 - name.size(), ' ') +
            (s.usable ? "usable: " : "unusable: ") + s.detail + "\n";
  }
  text.pop_back();  // CLI11 ends the version with its own newline
  return text;
}

}  // namespace snee
