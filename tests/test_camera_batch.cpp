// Batched camera-ray generation against the scalar reference: the exact integer division it
// relies on, slot-chunk loads and stores, and generate_camera_rays, whose every path-state field
// must equal the scalar random_block + camera_ray result, for contiguous and scattered slots and
// for every tail length: bit for bit for a pinhole, within the sincos bound of
// kernels/simd/README.md for a thin lens.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "kernels/physics/camera.h"
#include "kernels/physics/rng.h"
#include "kernels/simd/divide.h"
#include "kernels/simd/slot_chunk.h"
#include "kernels/stages/stages.h"
#include "tests/support/render_helpers.h"

namespace snee {
namespace {

using simd::kLanes;
using simd::UintBatch;

TEST(CameraBatch, DivideIsExact) {
  std::mt19937 engine(4);
  for (const uint32_t d : {1u, 2u, 3u, 7u, 37u, 640u, 1920u, 4095u, 32768u, 65536u}) {
    const uint64_t limit = std::min<uint64_t>(uint64_t{1} << 31, uint64_t{d} << 22);
    for (int trial = 0; trial < 4000; ++trial) {
      alignas(64) uint32_t n[kLanes];
      for (size_t i = 0; i < kLanes; ++i) {
        // Multiples of d and their neighbours are where a float estimate goes wrong.
        const uint64_t base = trial % 2 ? engine() % limit : (engine() % (limit / d)) * d;
        const int64_t offset = trial % 2 ? 0 : static_cast<int64_t>(i % 3) - 1;
        n[i] = static_cast<uint32_t>(
            std::clamp<int64_t>(static_cast<int64_t>(base) + offset, 0, int64_t(limit) - 1));
      }
      if (trial == 0) n[0] = static_cast<uint32_t>(limit - 1);
      const simd::QuotientRemainder qr = simd::divide(UintBatch::load_aligned(n), d);
      alignas(64) uint32_t q[kLanes], r[kLanes];
      qr.quotient.store_aligned(q);
      qr.remainder.store_aligned(r);
      for (size_t i = 0; i < kLanes; ++i) {
        ASSERT_EQ(q[i], n[i] / d) << n[i] << " / " << d;
        ASSERT_EQ(r[i], n[i] % d) << n[i] << " % " << d;
      }
    }
  }
}

TEST(CameraBatch, SlotChunkStoresOnlyItsLanes) {
  std::vector<uint32_t> order(64);
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937(5));
  for (const bool contiguous : {true, false}) {
    for (size_t count = 1; count <= kLanes; ++count) {
      std::vector<uint32_t> slots(count);
      for (size_t i = 0; i < count; ++i) slots[i] = contiguous ? 7 + uint32_t(i) : order[i];
      std::vector<float> source(64), target(64, -1.0f);
      for (size_t i = 0; i < 64; ++i) source[i] = static_cast<float>(i) + 0.5f;
      const simd::SlotChunk chunk(slots.data(), count);
      EXPECT_EQ(chunk.contiguous(), contiguous && count == kLanes);
      chunk.store(target.data(), chunk.load(source.data()));
      for (size_t s = 0; s < 64; ++s) {
        const bool listed = std::find(slots.begin(), slots.end(), s) != slots.end();
        EXPECT_EQ(target[s], listed ? source[s] : -1.0f) << "slot " << s << " count " << count;
      }
    }
  }
}

// Thin-lens origins and directions: xsimd's sincos of the disk angle is not libm's.
constexpr float kLensBound = 0x1p-21f;

// Pinhole (false) or thin lens (true).
class GenerateCameraRays : public ::testing::TestWithParam<bool> {
 protected:
  GenerateCameraRays()
      : scene_(odd_sized(test::sphere_scene(Material{}, Medium{}, 8), GetParam())),
        embree_(scene_),
        lights_(scene_),
        ctx_(scene_, embree_, lights_, Integrator::kPathTracer, 9, 16, SneeOptions{}) {}

  static Scene odd_sized(Scene s, bool thin_lens) {
    s.camera.width = 37;
    s.camera.height = 23;
    if (thin_lens) {
      s.camera.aperture_radius = 0.3f;
      s.camera.focus_distance = 2.5f;
    }
    return s;
  }

  // Generates paths for (pixel, sample) pairs in `slots`, in calls of at most `per_call`, and
  // checks every written field against the scalar reference and every other slot untouched.
  void check(const std::vector<uint32_t>& slots, size_t per_call) {
    const size_t n = slots.size();
    std::vector<uint32_t> pixels(n), samples(n);
    const uint32_t pixel_count = static_cast<uint32_t>(ctx_.width * ctx_.height);
    for (size_t i = 0; i < n; ++i) {
      pixels[i] = static_cast<uint32_t>(i) % pixel_count;
      samples[i] = 3 + static_cast<uint32_t>(i) / pixel_count;
    }
    PathState state(capacity_, false);
    const uint32_t sentinel = 0x7FC12345u;  // a NaN payload as float, a large value as int
#define SNEE_FILL_FIELD(type, name) \
  std::fill_n(reinterpret_cast<uint32_t*>(state.name), state.capacity(), sentinel);
    SNEE_PATH_FIELDS(SNEE_FILL_FIELD)
#undef SNEE_FILL_FIELD
    StageQueues q(capacity_);
    KernelCounters counters;
    for (size_t begin = 0; begin < n; begin += per_call) {
      const size_t count = std::min(per_call, n - begin);
      generate_camera_rays(ctx_, state, slots.data() + begin, pixels.data() + begin,
                           samples.data() + begin, count, q, counters);
    }
    ASSERT_EQ(q.extend.size(), n);
    EXPECT_EQ(counters.paths, n);
    const FilmCamera camera = film_camera(ctx_.camera, ctx_.width, ctx_.height);
    float worst = 0;
    std::vector<bool> listed(state.capacity(), false);
    for (size_t i = 0; i < n; ++i) {
      const uint32_t s = slots[i];
      listed[s] = true;
      ASSERT_EQ(q.extend[i], s);
      const RandomBlock r = random_block(ctx_.seed, pixels[i], samples[i], 0, RngPurpose::kCamera);
      const CameraRayOf<float> want = camera_ray(camera, pixels[i], r);
      ASSERT_EQ(state.pixel[s], pixels[i]);
      ASSERT_EQ(state.sample[s], samples[i]);
      ASSERT_EQ(state.event[s] | state.depth[s] | state.flags[s], 0u);
      ASSERT_EQ(state.medium[s], -1);
      ASSERT_EQ(state.throughput(s), Rgb(1.0f));
      ASSERT_EQ(state.radiance(s), Rgb(0.0f));
      ASSERT_EQ(state.mis_pdf[s], 0.0f);
      ASSERT_EQ(state.eta_scale[s], 1.0f);
      ASSERT_EQ(state.channel_probabilities(s), Rgb(1.0f / 3.0f));
      const Vec3 origin = state.origin(s), direction = state.direction(s);
      for (int c = 0; c < 3; ++c) {
        if (GetParam()) {
          const float aperture = scene_.camera.aperture_radius;
          worst = std::max({worst, std::fabs(origin[c] - want.origin[c]) / aperture,
                            std::fabs(direction[c] - want.direction[c])});
        } else {
          ASSERT_EQ(std::bit_cast<uint32_t>(origin[c]), std::bit_cast<uint32_t>(want.origin[c]));
          ASSERT_EQ(std::bit_cast<uint32_t>(direction[c]),
                    std::bit_cast<uint32_t>(want.direction[c]))
              << "pixel " << pixels[i] << " component " << c;
        }
      }
    }
    EXPECT_LE(worst, kLensBound) << "largest component difference";
    for (size_t s = 0; s < state.capacity(); ++s) {
      if (listed[s]) continue;
      ASSERT_EQ(state.pixel[s], sentinel) << "slot " << s;
      ASSERT_EQ(std::bit_cast<uint32_t>(state.dir_z[s]), sentinel) << "slot " << s;
    }
  }

  static constexpr size_t capacity_ = 2048;
  Scene scene_;
  EmbreeScene embree_;
  LightTable lights_;
  KernelContext ctx_;
};

TEST_P(GenerateCameraRays, ContiguousSlotsMatchScalar) {
  std::vector<uint32_t> slots(37 * 23 * 2);
  std::iota(slots.begin(), slots.end(), 0u);
  check(slots, slots.size());
}

TEST_P(GenerateCameraRays, ScatteredSlotsMatchScalar) {
  std::vector<uint32_t> slots(capacity_);
  std::iota(slots.begin(), slots.end(), 0u);
  std::shuffle(slots.begin(), slots.end(), std::mt19937(6));
  slots.resize(1500);
  check(slots, slots.size());
}

TEST_P(GenerateCameraRays, EveryTailLengthMatchesScalar) {
  for (size_t per_call = 1; per_call <= 3 * kLanes + 1; ++per_call) {
    std::vector<uint32_t> slots(200);
    std::iota(slots.begin(), slots.end(), 5u);  // contiguous runs that start off alignment
    check(slots, per_call);
  }
}

INSTANTIATE_TEST_SUITE_P(Camera, GenerateCameraRays, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& p) {
                           return p.param ? "ThinLens" : "Pinhole";
                         });

}  // namespace
}  // namespace snee
