#include "tests/support/statistics.h"

#include <cmath>
#include <limits>

namespace snee::test {

double MeanEstimator::standard_error() const {
  return n_ > 1 ? std::sqrt(variance() / static_cast<double>(n_))
                : std::numeric_limits<double>::infinity();
}

double z_score(double a, double se_a, double b, double se_b) {
  const double se = std::sqrt(se_a * se_a + se_b * se_b);
  if (se == 0) return a == b ? 0.0 : std::numeric_limits<double>::infinity();
  return std::fabs(a - b) / se;
}

namespace {

// Regularized lower incomplete gamma P(a, x) by its power series (converges for x < a + 1).
double gamma_p_series(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < 10000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::fabs(term) < std::fabs(sum) * 1e-15) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Regularized upper incomplete gamma Q(a, x) by Lentz's continued fraction (x >= a + 1).
double gamma_q_continued_fraction(double a, double x) {
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1.0) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

double chi2_survival(double x, double dof) {
  if (x <= 0) return 1.0;
  const double a = 0.5 * dof, hx = 0.5 * x;
  return hx < a + 1.0 ? 1.0 - gamma_p_series(a, hx) : gamma_q_continued_fraction(a, hx);
}

}  // namespace snee::test
