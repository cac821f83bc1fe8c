// What an EXR records about how it was made, beyond the film's own metadata, so a result can be
// reproduced or told apart months later: the command line, a hash of the scene document, every
// option that shapes the image, the preview settings and the build's SIMD architecture.
#pragma once

#include <string>
#include <string_view>

#include "scene/film.h"
#include "scene/scene_loader.h"
#include "scene/tone_map.h"
#include "scheduler/render.h"

namespace snee {

// 64-bit FNV-1a of `bytes` as 16 lowercase hex digits: not cryptographic, it tells scene
// versions apart, it does not authenticate them.
std::string fnv1a64_hex(std::string_view bytes);

// "fnv1a64:HEX" of a scene file's bytes, or of a built-in scene's canonical JSON document.
std::string scene_digest(const std::string& scene_spec, const LoadedScene& loaded);

// This process's command line, arguments joined by spaces, each with a space, quote or
// backslash in it single-quoted (read from /proc/self/cmdline; empty where there is none).
std::string command_line();

// snee:command_line, snee:scene_hash ("fnv1a64:HEX of <what was hashed>": a scene file's
// bytes, a built-in scene's canonical JSON document), snee:render_options (JSON),
// snee:sample_clamp ("off" or the value, marked biased) and snee:simd (the SIMD level that
// renders and why).
ExrAttributes render_settings_attributes(const std::string& scene_spec, const LoadedScene& loaded,
                                         const RenderOptions& options, const ToneMap& tone);

}  // namespace snee
