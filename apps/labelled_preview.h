// An 8-bit preview with text drawn over it (OpenImageIO's text rendering, which needs a
// TrueType font file), for the images whose meaning needs words: `snee compare`'s contact
// sheet. Text is drawn after tone mapping, so it is white whatever the exposure.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "scene/film.h"
#include "scene/tone_map.h"

namespace snee {

inline constexpr int kLabelFontSize = 13;  // pixels from baseline to baseline is 17
inline constexpr int kLabelLineHeight = 17;

struct TextLabel {
  int x = 0, y = 0;  // the baseline's left end (its centre when `centred`)
  std::string text;
  // Columns the text may cover: a label too long for its tile is cut off there rather than
  // spilling into the next one.
  int clip_begin = 0, clip_end = 0;
  bool centred = false;
};

// The fonts tried when none is given, the first that exists wins: DejaVu Sans where Debian
// (fonts-dejavu-core, installed by scripts/setup.sh), Fedora and Arch put it.
std::vector<std::filesystem::path> default_label_fonts();
// The first of `candidates` that is a regular file, if any.
std::optional<std::filesystem::path> find_label_font(
    const std::vector<std::filesystem::path>& candidates);

// Throws std::invalid_argument naming `font` when OpenImageIO cannot draw text with it.
void check_label_font(const std::filesystem::path& font);

// Writes `image` through `tone` with `labels` drawn in `font`, replacing `path` whole
// (apps/output_files.h). Without a font the labels are left out. Throws std::runtime_error
// naming the file or the font when writing or drawing fails.
void write_labelled_preview(const Film& image, const std::vector<TextLabel>& labels,
                            const std::optional<std::filesystem::path>& font,
                            const std::filesystem::path& path, const ToneMap& tone = {});

}  // namespace snee
