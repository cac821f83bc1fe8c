// Density grids in files: Mitsuba's binary .vol format (version 3, float32, one channel), the
// one heterogeneous media are commonly exchanged in without OpenVDB:
//   bytes 0-3   'V' 'O' 'L' 3
//   int32       encoding, 1 = float32
//   int32 x3    resolution nx, ny, nz
//   int32       channels, 1
//   float32 x6  the box: min x, y, z, then max x, y, z
//   float32     nx * ny * nz values, x fastest, then y, then z
// all little-endian.
#pragma once

#include <string>

#include "core/density_grid.h"
#include "scene/memory_budget.h"

namespace snee {

// The grid in `path`. Throws SceneError naming the file, the field and what was expected for a
// short or foreign header, a resolution or box that makes no grid, data that does not fill the
// grid exactly, a negative or non-finite value (with its voxel), or a grid over `budget`.
DensityGrid read_density_grid(const std::string& path, const MemoryBudget& budget);

// Writes `grid` as a .vol file (for tools and tests); throws SceneError if it cannot.
void write_density_grid(const std::string& path, const DensityGrid& grid);

// Checks that `grid` is one (resolution at least 1, box of positive extent, values that fill it,
// non-negative and finite) and sets max_value; throws SceneError "<where>: <what was expected>".
void validate_density_grid(DensityGrid& grid, const std::string& where);

}  // namespace snee
