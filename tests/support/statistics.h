// Statistics used by the test suite: running mean with standard error, z-tests, and the
// chi-square survival function (upper regularized incomplete gamma) for goodness-of-fit tests.
#pragma once

#include <cstdint>

namespace snee::test {

// Welford accumulator of i.i.d. samples.
class MeanEstimator {
 public:
  void add(double x) {
    ++n_;
    const double d = x - mean_;
    mean_ += d / static_cast<double>(n_);
    m2_ += d * (x - mean_);
  }
  int64_t count() const { return n_; }
  double mean() const { return mean_; }
  double variance() const { return n_ > 1 ? m2_ / static_cast<double>(n_ - 1) : 0.0; }
  double standard_error() const;

 private:
  int64_t n_ = 0;
  double mean_ = 0, m2_ = 0;
};

// |a - b| / sqrt(se_a^2 + se_b^2); agreement in this suite means z < 4 (tests/README.md).
double z_score(double a, double se_a, double b, double se_b);

// P(X >= x) for X ~ chi-square with dof degrees of freedom.
double chi2_survival(double x, double dof);

}  // namespace snee::test
