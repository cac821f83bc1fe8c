// Pixel indices of big images: the row-major index is formed in 64 bits, and the largest image a
// scene may ask for (65536 px per edge) still fits the 32-bit index path state keeps per pixel.
#include <gtest/gtest.h>

#include <cstdint>

#include "scheduler/work_unit.h"

namespace snee {
namespace {

TEST(WorkUnit, RowMajorIndexDoesNotOverflowIntOnBigImages) {
  // 40000 * 60000 = 2.4e9 > INT32_MAX: the int product wrapped to a negative index.
  EXPECT_EQ(row_major_index(7, 40000, 60000), uint64_t{2'400'000'007});
  // The last pixel of a 65536^2 film is the largest 32-bit index.
  EXPECT_EQ(row_major_index(65535, 65535, 65536), uint64_t{UINT32_MAX});
  EXPECT_EQ(row_major_index(3, 2, 10), 23u);
}

TEST(WorkUnit, PixelCountOfAWholeBigImageTile) {
  const WorkUnit unit{0, 0, 65536, 65536, 0, 2};
  EXPECT_EQ(unit.pixel_count(), int64_t{1} << 32);
  EXPECT_EQ(unit.sample_count(), size_t{1} << 33);
}

}  // namespace
}  // namespace snee
