// Checks the light-sampling tests share (test_lights.cpp, test_env_map_light.cpp): the
// agreement of an estimate with a closed form, Pearson's test of binned samples, and the
// round trip of every sample's pdf through the pdf MIS uses (LightTable::escaped_pdf,
// area_pdf).
#pragma once

#include <cfloat>
#include <cstdint>
#include <vector>

#include "kernels/physics/lights/light_table.h"
#include "scene/scene.h"
#include "tests/support/statistics.h"

namespace snee::test {

inline constexpr double kMinPValue = 1e-4;
inline constexpr double kMaxZ = 4;
inline constexpr int kSamples = 1'000'000;
// Recomputing a pdf from the sampled point takes a handful of float operations.
inline constexpr float kPdfRelativeTolerance = 64 * FLT_EPSILON;

// Pearson's test of counts against expected counts (all expected counts are large here).
double pearson_p_value(const std::vector<double>& observed, const std::vector<double>& expected);

// The estimate agrees with `expected` within kMaxZ standard errors.
void expect_agrees(const MeanEstimator& e, double expected, const char* what);

// The pdf of every sample agrees with the pdf MIS uses for the same direction or point.
void expect_round_trip(const Scene& scene, const LightTable& lights, Vec3 p, uint64_t seed);

}  // namespace snee::test
