// The picture `snee compare` writes: the paper's split view and the error maps in one image.
//   top row:    [left half: first render | right half: second render]  [reference]
//   bottom row: [error map of each render, in the order given]
// Tiles are separated by a grey gutter; the layout is fixed so the image needs no labels (the
// compare JSON names the renders in order).
#pragma once

#include <vector>

#include "scene/film.h"

namespace snee {

// renders: at least one, all of the reference's size; with one render the top-left tile is
// that render alone. errors: one per render (apps/image_error.h).
Film contact_sheet(const Film& reference, const std::vector<const Film*>& renders,
                   const std::vector<Film>& errors);

}  // namespace snee
