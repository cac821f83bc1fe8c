#include "apps/render_settings.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>

#include "apps/simd_option.h"
#include "apps/stats_json.h"

namespace snee {
namespace {

std::string shell_quoted(const std::string& argument) {
  if (!argument.empty() && argument.find_first_of(" \t\n'\"\\$") == std::string::npos)
    return argument;
  std::string q = "'";
  for (const char c : argument) {
    if (c == '\'')
      q += "'\\''";
    else
      q += c;
  }
  return q + "'";
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string format_float(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", value);
  return buf;
}

}  // namespace

std::string fnv1a64_hex(std::string_view bytes) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::string scene_digest(const std::string& spec, const LoadedScene& loaded) {
  return "fnv1a64:" +
         fnv1a64_hex(spec.starts_with("builtin:") ? loaded.canonical.dump() : read_bytes(spec));
}

std::string command_line() {
  const std::string raw = read_bytes("/proc/self/cmdline");
  std::string line, argument;
  std::istringstream in(raw);
  while (std::getline(in, argument, '\0')) {
    if (!line.empty()) line += ' ';
    line += shell_quoted(argument);
  }
  return line;
}

ExrAttributes render_settings_attributes(const std::string& scene_spec, const LoadedScene& loaded,
                                         const RenderOptions& options, const ToneMap& tone) {
  const Camera& camera = loaded.scene.camera;
  const nlohmann::ordered_json render_options = {
      {"integrator", options.integrator},
      {"spp", options.spp},
      {"seed", options.seed},
      {"max_depth", options.max_depth},
      {"light_selection", light_selection_name(options.light_selection)},
      {"resolution", {{"width", camera.width}, {"height", camera.height}}},
      {"schedule", options.schedule},
      {"queue_capacity", options.queue_capacity},
      {"tile_size", options.tile_size},
      {"samples_per_unit", options.samples_per_unit},
      {"threads", options.threads},
      {"sample_clamp", options.sample_clamp},
      {"aovs", aov_list(options.aovs)},
      {"snee_options", snee_options_json(options.snee)},
      {"preview",
       {{"tone_curve", tone.curve == ToneCurve::kFilmic ? "filmic" : "clamp"},
        {"exposure_ev", tone.exposure_ev}}},
  };
  const std::string clamp =
      options.sample_clamp > 0
          ? format_float(options.sample_clamp) + " (biased: each sample's RGB clipped to it)"
          : "off";
  return {
      {"snee:command_line", command_line()},
      {"snee:scene_hash",
       scene_digest(scene_spec, loaded) + (scene_spec.starts_with("builtin:")
                                               ? " of the built-in scene's canonical JSON"
                                               : " of the bytes of " + scene_spec)},
      {"snee:render_options", render_options.dump()},
      {"snee:sample_clamp", clamp},
      {"snee:simd", simd_choice_text(options.simd, options.schedule)},
  };
}

}  // namespace snee
