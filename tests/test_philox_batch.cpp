// The batched Philox4x32-10 must reproduce Random123's scalar generator bit for bit in every
// lane, for arbitrary keys and counters (not only the small values a render uses).
#include <gtest/gtest.h>

#include <bit>
#include <random>

#include "kernels/simd/philox_batch.h"
#include "tests/support/lanes.h"

namespace snee {
namespace {

using simd::kLanes;
using simd::UintBatch;

using Lanes = test::Lanes<uint32_t>;
using test::to_lanes;

TEST(PhiloxBatch, MulHiLoMatches64BitProduct) {
  std::mt19937 engine(1);
  const uint32_t edges[] = {0u, 1u, 2u, 0x7FFFFFFFu, 0x80000000u, 0xFFFFFFFEu, 0xFFFFFFFFu};
  for (int trial = 0; trial < 20000; ++trial) {
    Lanes a, b;
    for (size_t i = 0; i < kLanes; ++i) {
      a.v[i] = trial < 49 ? edges[(trial / 7 + i) % 7] : engine();
      b.v[i] = trial < 49 ? edges[trial % 7] : engine();
    }
    UintBatch hi, lo;
    simd::mul_hilo(a.batch(), b.batch(), &hi, &lo);
    const Lanes h = to_lanes(hi), l = to_lanes(lo);
    for (size_t i = 0; i < kLanes; ++i) {
      const uint64_t p = uint64_t{a.v[i]} * b.v[i];
      ASSERT_EQ(h.v[i], static_cast<uint32_t>(p >> 32)) << a.v[i] << " * " << b.v[i];
      ASSERT_EQ(l.v[i], static_cast<uint32_t>(p)) << a.v[i] << " * " << b.v[i];
    }
  }
}

TEST(PhiloxBatch, BitsMatchRandom123OverManyKeys) {
  std::mt19937 engine(2);
  using Philox = r123::Philox4x32;
  for (int trial = 0; trial < 20000; ++trial) {
    Lanes ctr[4], key[2];
    for (size_t i = 0; i < kLanes; ++i) {
      for (Lanes& c : ctr) c.v[i] = engine();
      for (Lanes& k : key) k.v[i] = engine();
    }
    const simd::PhiloxCounter out =
        simd::philox4x32_10({ctr[0].batch(), ctr[1].batch(), ctr[2].batch(), ctr[3].batch()},
                            {key[0].batch(), key[1].batch()});
    for (int w = 0; w < 4; ++w) {
      const Lanes got = to_lanes(out[static_cast<size_t>(w)]);
      for (size_t i = 0; i < kLanes; ++i) {
        const Philox::ctr_type c = {{ctr[0].v[i], ctr[1].v[i], ctr[2].v[i], ctr[3].v[i]}};
        const Philox::key_type k = {{key[0].v[i], key[1].v[i]}};
        ASSERT_EQ(got.v[i], Philox()(c, k)[static_cast<size_t>(w)]) << "trial " << trial;
      }
    }
  }
}

TEST(PhiloxBatch, RandomBlockMatchesScalarForEveryPurpose) {
  std::mt19937 engine(3);
  for (int trial = 0; trial < 4000; ++trial) {
    const uint32_t seed = trial < 100 ? static_cast<uint32_t>(trial) : engine();
    Lanes pixel, sample, event;
    for (size_t i = 0; i < kLanes; ++i) {
      // Render-like small values first, then arbitrary words.
      pixel.v[i] = trial < 2000 ? engine() % 65536 : engine();
      sample.v[i] = trial < 2000 ? engine() % 1024 : engine();
      event.v[i] = trial < 2000 ? engine() % 64 : engine();
    }
    for (uint32_t p = 0; p < static_cast<uint32_t>(RngPurpose::kCount); ++p) {
      const auto purpose = static_cast<RngPurpose>(p);
      const simd::RandomBlockBatch got =
          simd::random_block(seed, pixel.batch(), sample.batch(), event.batch(), purpose);
      alignas(64) float u[4][kLanes];
      for (size_t w = 0; w < 4; ++w) got.u[w].store_aligned(u[w]);
      for (size_t i = 0; i < kLanes; ++i) {
        const RandomBlock want = random_block(seed, pixel.v[i], sample.v[i], event.v[i], purpose);
        for (size_t w = 0; w < 4; ++w)
          ASSERT_EQ(std::bit_cast<uint32_t>(u[w][i]), std::bit_cast<uint32_t>(want.u[w]))
              << "seed " << seed << " purpose " << p << " word " << w;
      }
    }
  }
}

// The chunk form: a one-slot chunk takes the scalar shortcut, wider chunks the batch; lane 0
// (and, for full chunks, every lane) must carry the same bits either way.
TEST(PhiloxBatch, ChunkFormMatchesTheBatchOnItsActiveLanes) {
  std::mt19937 engine(4);
  for (int trial = 0; trial < 2000; ++trial) {
    Lanes pixel, sample, event;
    for (size_t i = 0; i < kLanes; ++i) {
      pixel.v[i] = engine() % 65536;
      sample.v[i] = engine() % 1024;
      event.v[i] = engine() % 64;
    }
    const auto purpose = static_cast<RngPurpose>(trial % static_cast<int>(RngPurpose::kCount));
    const simd::RandomBlockBatch batch =
        simd::random_block(7, pixel.batch(), sample.batch(), event.batch(), purpose);
    for (const size_t active : {size_t{1}, kLanes}) {
      const simd::RandomBlockBatch chunk =
          simd::random_block(7, pixel.batch(), sample.batch(), event.batch(), purpose, active);
      for (size_t w = 0; w < 4; ++w)
        for (size_t i = 0; i < active; ++i)
          ASSERT_EQ(std::bit_cast<uint32_t>(chunk.u[w].get(i)),
                    std::bit_cast<uint32_t>(batch.u[w].get(i)))
              << "active " << active << " lane " << i;
    }
  }
}

}  // namespace
}  // namespace snee
