#include "apps/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "apps/image_error.h"

namespace snee {

namespace {

constexpr int kGutter = 4;
const Rgb kGutterColour(0.2f);
// Dark enough behind white text to read at a glance.
const Rgb kStripColour(0.01f);
constexpr int kTextMargin = 4;
constexpr int kLabelStrip = 2 * kLabelLineHeight + 6;  // two lines of text and their margins
constexpr int kBarHeight = 12;
constexpr int kTickLength = 4;
// A caption line, the bar, its ticks and a line of tick labels.
constexpr int kBarStrip = kLabelLineHeight + kBarHeight + kTickLength + kLabelLineHeight + 6;

void fill(Film& sheet, int x0, int y0, int width, int height, const Rgb& colour) {
  for (int y = y0; y < y0 + height; ++y)
    for (int x = x0; x < x0 + width; ++x) sheet.at(x, y) = colour;
}

// Copies columns [x_begin, x_end) of tile, each pixel as a zoom x zoom block, into the sheet
// with the tile's top-left corner at (x0, y0).
void paste(Film& sheet, const Film& tile, int zoom, int x0, int y0, int x_begin, int x_end) {
  for (int y = 0; y < tile.height * zoom; ++y)
    for (int x = x_begin * zoom; x < x_end * zoom; ++x)
      sheet.at(x0 + x, y0 + y) = tile.at(x / zoom, y / zoom);
}

std::string format(const char* pattern, auto... values) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, values...);
  return text;
}

// Two lines of text in the strip under the tile whose left edge is x0 and bottom edge y0.
void caption(ContactSheet& sheet, int x0, int y0, int width, const std::string& first,
             const std::string& second) {
  const int x = x0 + kTextMargin, end = x0 + width;
  sheet.labels.push_back({x, y0 + kLabelLineHeight, first, x0, end});
  if (!second.empty()) sheet.labels.push_back({x, y0 + 2 * kLabelLineHeight, second, x0, end});
}

// The error maps' scale across the sheet's width at height y0, one tick per decade.
void colour_bar(ContactSheet& sheet, int y0) {
  Film& image = sheet.image;
  const int x0 = 2 * kTextMargin + 12, width = image.width - 2 * x0;
  sheet.labels.push_back({kTextMargin, y0 + kLabelLineHeight - 3,
                          "error maps: (x - ref)^2 / (ref^2 + 0.01) per pixel, log scale", 0,
                          image.width});
  const int bar_top = y0 + kLabelLineHeight;
  constexpr int kDecades = kErrorMapHighestDecade - kErrorMapLowestDecade;
  for (int x = 0; x < width; ++x) {
    const double decade = kErrorMapLowestDecade + kDecades * x / double(std::max(1, width - 1));
    fill(image, x0 + x, bar_top, 1, kBarHeight, error_colour(std::pow(10.0, decade)));
  }
  for (int d = 0; d <= kDecades; ++d) {
    const int x = x0 + static_cast<int>(std::lround(d * (width - 1) / double(kDecades)));
    fill(image, x, bar_top + kBarHeight, 1, kTickLength, Rgb(1.0f));
    sheet.labels.push_back({x, bar_top + kBarHeight + kTickLength + kLabelLineHeight - 4,
                            format("1e%d", kErrorMapLowestDecade + d), 0, image.width, true});
  }
}

}  // namespace

ContactSheet contact_sheet(const Film& reference, const std::string& reference_text,
                           const std::vector<SheetRender>& renders) {
  ContactSheet sheet;
  const int w = reference.width, h = reference.height;
  sheet.zoom = std::max(1, (kMinSheetTileWidth + w - 1) / w);
  const int tile_w = w * sheet.zoom, tile_h = h * sheet.zoom;
  const int columns = std::max<int>(2, static_cast<int>(renders.size()));
  const int row = tile_h + kLabelStrip + kGutter;
  Film& image = sheet.image;
  image.width = columns * tile_w + (columns - 1) * kGutter;
  image.height = 2 * row + kBarStrip;
  image.mean.assign(static_cast<size_t>(image.width) * image.height, kGutterColour);

  const SheetRender& left = renders.front();
  const SheetRender& right = renders.size() > 1 ? renders[1] : left;
  const int z = sheet.zoom;
  paste(image, *left.film, z, 0, 0, 0, w / 2);
  paste(image, *right.film, z, 0, 0, w / 2, w);
  const std::string zoomed = z > 1 ? format(" (shown %dx)", z) : "";
  fill(image, 0, tile_h, tile_w, kLabelStrip, kStripColour);
  caption(sheet, 0, tile_h, tile_w, "left: " + left.name + "   right: " + right.name,
          "split view" + zoomed);
  const int ref_x = tile_w + kGutter;
  paste(image, reference, z, ref_x, 0, 0, w);
  fill(image, ref_x, tile_h, tile_w, kLabelStrip, kStripColour);
  caption(sheet, ref_x, tile_h, tile_w, reference_text, zoomed.empty() ? "" : zoomed.substr(1));

  for (size_t i = 0; i < renders.size(); ++i) {
    const SheetRender& r = renders[i];
    const int x0 = static_cast<int>(i) * (tile_w + kGutter);
    paste(image, r.error, z, x0, row, 0, w);
    fill(image, x0, row + tile_h, tile_w, kLabelStrip, kStripColour);
    caption(sheet, x0, row + tile_h, tile_w,
            format("%s: %d spp, %.2f s", r.name.c_str(), r.spp, r.seconds),
            format("relMSE %.3g (error map)", r.relative_mse));
  }
  fill(image, 0, 2 * row, image.width, kBarStrip, kStripColour);
  colour_bar(sheet, 2 * row);
  return sheet;
}

}  // namespace snee
