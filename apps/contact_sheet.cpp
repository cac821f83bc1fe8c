#include "apps/contact_sheet.h"

#include <algorithm>

namespace snee {

namespace {

constexpr int kGutter = 4;
const Rgb kGutterColour(0.2f);

// Copies columns [x_begin, x_end) of tile into the sheet with its top-left corner at (x0, y0).
void paste(Film& sheet, const Film& tile, int x0, int y0, int x_begin, int x_end) {
  for (int y = 0; y < tile.height; ++y)
    for (int x = x_begin; x < x_end; ++x) sheet.at(x0 + x, y0 + y) = tile.at(x, y);
}

}  // namespace

Film contact_sheet(const Film& reference, const std::vector<const Film*>& renders,
                   const std::vector<Film>& errors) {
  const int w = reference.width, h = reference.height;
  const int columns = std::max<int>(2, static_cast<int>(errors.size()));
  Film sheet;
  sheet.width = columns * w + (columns - 1) * kGutter;
  sheet.height = 2 * h + kGutter;
  sheet.mean.assign(static_cast<size_t>(sheet.width) * sheet.height, kGutterColour);

  const Film& left = *renders.front();
  const Film& right = renders.size() > 1 ? *renders[1] : left;
  paste(sheet, left, 0, 0, 0, w / 2);
  paste(sheet, right, 0, 0, w / 2, w);
  paste(sheet, reference, w + kGutter, 0, 0, w);
  for (size_t i = 0; i < errors.size(); ++i)
    paste(sheet, errors[i], static_cast<int>(i) * (w + kGutter), h + kGutter, 0, w);
  return sheet;
}

}  // namespace snee
