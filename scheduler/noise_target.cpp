#include "scheduler/noise_target.h"

#include <algorithm>
#include <cmath>

namespace snee {

double relative_standard_error(const double mean[3], const double variance_of_mean[3]) {
  constexpr double kWeights[3] = {0.2126, 0.7152, 0.0722};
  double luminance = 0, error = 0;
  for (int c = 0; c < 3; ++c) {
    luminance += kWeights[c] * mean[c];
    error += kWeights[c] * std::sqrt(std::max(0.0, variance_of_mean[c]));
  }
  return error / std::max(std::abs(luminance), kNoiseFloor);
}

}  // namespace snee
