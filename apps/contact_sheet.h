// The picture `snee compare` writes: the paper's split view and the error maps in one image,
// each tile labelled, with the error maps' colour scale below them.
//   top row:    [left half: first render | right half: second render]  [reference]
//   bottom row: [error map of each render, in the order given]
//   colour bar: the error scale of apps/image_error.h, a tick and a label per decade
// Under every tile a strip holds two lines of text (which render, its spp and time, its
// error). Images narrower than kMinSheetTileWidth are enlarged by a whole factor, pixel by
// pixel, so the labels fit and the noise stays visible as it is.
#pragma once

#include <string>
#include <vector>

#include "apps/labelled_preview.h"
#include "scene/film.h"

namespace snee {

inline constexpr int kMinSheetTileWidth = 200;

struct SheetRender {
  std::string name;
  const Film* film = nullptr;  // the reference's size
  Film error;                  // apps/image_error.h error_image
  int spp = 0;
  double seconds = 0;
  double relative_mse = 0;
};

struct ContactSheet {
  Film image;  // linear radiance, labels not drawn
  std::vector<TextLabel> labels;
  int zoom = 1;  // how many sheet pixels wide and high one image pixel is
};

// renders: at least one; with one the split view is that render alone. reference_text
// describes the reference (e.g. "reference: snee, 1024 spp").
ContactSheet contact_sheet(const Film& reference, const std::string& reference_text,
                           const std::vector<SheetRender>& renders);

}  // namespace snee
