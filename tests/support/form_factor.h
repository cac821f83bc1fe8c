// Closed-form radiative-transfer results that tests compare renders and light samplers to.
#pragma once

#include <cmath>

namespace snee::test {

// Form factor from a point to a parallel a x b rectangle whose corner lies straight above it at
// height c (a standard radiative-transfer table entry, e.g. Howell's catalogue, case B-3).
inline double corner_form_factor(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * M_PI);
}

}  // namespace snee::test
