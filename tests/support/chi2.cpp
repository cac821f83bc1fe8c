#include "tests/support/chi2.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <vector>

#include "tests/support/statistics.h"

namespace snee::test {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Each cell starts from this many Simpson panels per axis, so a feature must be narrower than
// a quarter cell (and invisible at its nodes) to be missed; recursion then refines.
constexpr int kInitialPanels = 4;
constexpr int kMaxDepth = 16;
// Relative tolerances sit above float round-off in the pdfs (~1e-7), so noise cannot force
// recursion to kMaxDepth; the outer (cos theta) one is looser than the inner one it integrates.
constexpr double kInnerRelative = 1e-7;
constexpr double kOuterRelative = 1e-6;
constexpr double kInf = std::numeric_limits<double>::infinity();

double adaptive_simpson(const std::function<double(double)>& f, double a, double b, double fa,
                        double fm, double fb, double whole, double eps, double rel, int depth) {
  const double m = 0.5 * (a + b);
  const double lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
  const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
  const double diff = left + right - whole;
  if (depth >= kMaxDepth || std::fabs(diff) <= 15.0 * std::max(eps, rel * std::fabs(left + right)))
    return left + right + diff / 15.0;
  return adaptive_simpson(f, a, m, fa, flm, fm, left, 0.5 * eps, rel, depth + 1) +
         adaptive_simpson(f, m, b, fm, frm, fb, right, 0.5 * eps, rel, depth + 1);
}

// Integral over [a, b] (finite) with absolute tolerance eps or relative tolerance rel.
double integrate_finite(const std::function<double(double)>& f, double a, double b, double eps,
                        double rel) {
  const double h = (b - a) / kInitialPanels;
  double sum = 0;
  double fa = f(a);
  for (int i = 0; i < kInitialPanels; ++i) {
    const double x0 = a + i * h, x1 = (i + 1 == kInitialPanels) ? b : x0 + h;
    const double fm = f(0.5 * (x0 + x1)), fb = f(x1);
    const double whole = (x1 - x0) / 6.0 * (fa + 4.0 * fm + fb);
    sum += adaptive_simpson(f, x0, x1, fa, fm, fb, whole, eps / kInitialPanels, rel, 0);
    fa = fb;
  }
  return sum;
}

// Maps the half line to y in [0, 1); the integrand in y includes dt/dy. Nodes at y = 1 are
// pulled in slightly so that heavy (1/t^2) tails contribute their finite limit, not NaN.
double half_line_integrand(const std::function<double(double)>& f, double y, double scale) {
  y = std::min(y, 1.0 - 1e-12);
  const double t = scale * y / (1.0 - y);
  return f(t) * scale / ((1.0 - y) * (1.0 - y));
}

// The sphere cell grid: cos theta in [c0, c1] split into cos_bins, phi in [0, 2 pi) into
// phi_bins, about `axis`.
struct SphereGrid {
  Frame frame;
  double c0, c1;
  int cos_bins, phi_bins;

  double cos_width() const { return (c1 - c0) / cos_bins; }
  double phi_width() const { return kTwoPi / phi_bins; }

  double integrate_cell(const std::function<double(Vec3)>& f, int ic, int ip, double eps) const {
    const double ca = c0 + ic * cos_width(), cb = (ic + 1 == cos_bins) ? c1 : ca + cos_width();
    const double pa = ip * phi_width(), pb = pa + phi_width();
    const double inner_eps = eps / (cb - ca);
    const auto over_phi = [&](double c) {
      const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
      return integrate_finite(
          [&](double phi) {
            const Vec3 local(static_cast<float>(s * std::cos(phi)),
                             static_cast<float>(s * std::sin(phi)), static_cast<float>(c));
            return f(frame.to_world(local));
          },
          pa, pb, inner_eps, kInnerRelative);
    };
    return integrate_finite(over_phi, ca, cb, eps, kOuterRelative);
  }

  // Cell of a direction, or -1 if it lies outside [c0, c1].
  int cell_of(Vec3 w) const {
    const Vec3 local = frame.to_local(w);
    const double c = std::clamp(static_cast<double>(local.z), -1.0, 1.0);
    if (c < c0) return -1;
    double phi = std::atan2(static_cast<double>(local.y), static_cast<double>(local.x));
    if (phi < 0) phi += kTwoPi;
    const int ic = std::min(cos_bins - 1, static_cast<int>((c - c0) / cos_width()));
    const int ip = std::min(phi_bins - 1, static_cast<int>(phi / phi_width()));
    return ic * phi_bins + ip;
  }
};

struct Cell {
  double expected = 0;
  double observed = 0;
  std::string label;
};

// Pools small cells (smallest first, as in Mitsuba's chi-square test), computes Pearson's
// statistic and fills the result. `cells` holds counts; the last cell is the failure cell.
void evaluate(std::vector<Cell> cells, int64_t samples, double min_expected, Chi2Result* r) {
  std::sort(cells.begin(), cells.end(),
            [](const Cell& a, const Cell& b) { return a.expected < b.expected; });
  std::vector<Cell> merged;
  Cell pool{0, 0, "pooled small cells"};
  size_t i = 0;
  for (; i < cells.size() && cells[i].expected < min_expected; ++i) {
    pool.expected += cells[i].expected;
    pool.observed += cells[i].observed;
  }
  if (pool.expected > 0 || pool.observed > 0) {
    if (pool.expected < min_expected && i < cells.size()) {
      pool.expected += cells[i].expected;
      pool.observed += cells[i].observed;
      ++i;
    }
    merged.push_back(pool);
  }
  for (; i < cells.size(); ++i) merged.push_back(cells[i]);

  std::vector<std::pair<double, const Cell*>> contributions;
  double statistic = 0;
  for (const Cell& c : merged) {
    const double term = c.expected > 0
                            ? (c.observed - c.expected) * (c.observed - c.expected) / c.expected
                            : (c.observed > 0 ? kInf : 0.0);
    statistic += term;
    contributions.emplace_back(term, &c);
  }
  r->statistic = statistic;
  r->dof = static_cast<int>(merged.size()) - 1;
  r->p_value = r->dof > 0 ? chi2_survival(statistic, r->dof) : 1.0;
  if (!std::isfinite(statistic)) r->p_value = 0;

  std::sort(contributions.begin(), contributions.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  std::ostringstream out;
  out << "chi2 = " << statistic << " with " << r->dof << " dof, p = " << r->p_value
      << "; pdf integral = " << r->integral << ", success fraction = " << r->success_fraction
      << " of " << samples << " samples; largest contributions:";
  for (size_t k = 0; k < std::min<size_t>(5, contributions.size()); ++k) {
    const Cell& c = *contributions[k].second;
    out << "\n  " << c.label << ": observed " << c.observed << ", expected " << c.expected;
  }
  r->report = out.str();
}

Chi2Result malformed(const std::string& what) {
  Chi2Result r;
  r.p_value = 0;
  r.report = "malformed sample: " + what;
  return r;
}

}  // namespace

Chi2Result chi2_sphere(const std::function<std::optional<Vec3>()>& sample,
                       const std::function<double(Vec3)>& pdf, const SphereChi2Options& options) {
  const SphereGrid grid{Frame::from_normal(normalize(options.axis)), options.cos_min, 1.0,
                        options.cos_bins, options.phi_bins};
  const bool has_rest = options.cos_min > -1.0;
  const SphereGrid rest{grid.frame, -1.0, options.cos_min, options.cos_bins, options.phi_bins};
  const int n_grid = options.cos_bins * options.phi_bins;

  std::vector<Cell> cells(n_grid + 2);
  const double n = static_cast<double>(options.samples);
  int64_t successes = 0;
  for (int64_t k = 0; k < options.samples; ++k) {
    const std::optional<Vec3> w = sample();
    if (!w) {
      cells[n_grid + 1].observed += 1;
      continue;
    }
    if (!is_finite(*w) || std::fabs(length(*w) - 1.0f) > 1e-3f) {
      std::ostringstream s;
      s << "direction (" << w->x << ", " << w->y << ", " << w->z << ")";
      return malformed(s.str());
    }
    ++successes;
    const int cell = grid.cell_of(*w);
    cells[cell >= 0 ? cell : n_grid].observed += 1;
  }

  // Half a hundredth of a count per cell keeps quadrature error far below sampling noise.
  const double eps = 0.005 / n;
  double integral = 0;
  for (int ic = 0; ic < options.cos_bins; ++ic) {
    for (int ip = 0; ip < options.phi_bins; ++ip) {
      const double p = grid.integrate_cell(pdf, ic, ip, eps);
      integral += p;
      Cell& c = cells[ic * options.phi_bins + ip];
      c.expected = p * n;
      std::ostringstream s;
      s << "cos [" << grid.c0 + ic * grid.cos_width() << ", "
        << grid.c0 + (ic + 1) * grid.cos_width() << "] phi [" << ip * grid.phi_width() << ", "
        << (ip + 1) * grid.phi_width() << "]";
      c.label = s.str();
    }
  }
  double rest_integral = 0;
  if (has_rest) {
    for (int ic = 0; ic < options.cos_bins; ++ic)
      for (int ip = 0; ip < options.phi_bins; ++ip)
        rest_integral += rest.integrate_cell(pdf, ic, ip, eps);
  }
  integral += rest_integral;
  cells[n_grid] = {rest_integral * n, cells[n_grid].observed, "outside the binned cap"};
  cells[n_grid + 1] = {std::max(0.0, 1.0 - integral) * n, cells[n_grid + 1].observed, "failures"};

  Chi2Result r;
  r.integral = integral;
  r.success_fraction = static_cast<double>(successes) / n;
  evaluate(std::move(cells), options.samples, options.min_expected, &r);
  return r;
}

Chi2Result chi2_distance(const std::function<std::optional<double>()>& sample,
                         const std::function<double(double)>& pdf,
                         const DistanceChi2Options& options) {
  std::vector<Cell> cells(options.bins + 1);
  const double n = static_cast<double>(options.samples);
  int64_t successes = 0;
  for (int64_t k = 0; k < options.samples; ++k) {
    const std::optional<double> t = sample();
    if (!t || *t == kInf) {
      cells[options.bins].observed += 1;
      continue;
    }
    if (!(*t >= 0)) return malformed("distance " + std::to_string(*t));
    ++successes;
    const double y = *t / (*t + options.scale);
    cells[std::min(options.bins - 1, static_cast<int>(y * options.bins))].observed += 1;
  }

  const double eps = 0.005 / n;
  const auto g = [&](double y) { return half_line_integrand(pdf, y, options.scale); };
  double integral = 0;
  for (int b = 0; b < options.bins; ++b) {
    const double ya = static_cast<double>(b) / options.bins;
    const double yb = static_cast<double>(b + 1) / options.bins;
    const double p = integrate_finite(g, ya, yb, eps, kInnerRelative);
    integral += p;
    const double ta = options.scale * ya / (1 - ya);
    cells[b].expected = p * n;
    cells[b].label = "t in [" + std::to_string(ta) + ", " +
                     (b + 1 == options.bins ? std::string("inf")
                                            : std::to_string(options.scale * yb / (1 - yb))) +
                     "]";
  }
  cells[options.bins].expected = std::max(0.0, 1.0 - integral) * n;
  cells[options.bins].label = "failures / infinite distances";

  Chi2Result r;
  r.integral = integral;
  r.success_fraction = static_cast<double>(successes) / n;
  evaluate(std::move(cells), options.samples, options.min_expected, &r);
  return r;
}

double integrate_sphere(const std::function<double(Vec3)>& f, Vec3 axis, int cos_bins,
                        int phi_bins) {
  const SphereGrid grid{Frame::from_normal(normalize(axis)), -1.0, 1.0, cos_bins, phi_bins};
  const double eps = 1e-10 / (cos_bins * phi_bins);
  double sum = 0;
  for (int ic = 0; ic < cos_bins; ++ic)
    for (int ip = 0; ip < phi_bins; ++ip) sum += grid.integrate_cell(f, ic, ip, eps);
  return sum;
}

double integrate_interval(const std::function<double(double)>& f, double a, double b,
                          double scale) {
  constexpr double kEps = 1e-10;
  if (b != kInf) return integrate_finite(f, a, b, kEps, kInnerRelative);
  const double ya = a / (a + scale);
  return integrate_finite([&](double y) { return half_line_integrand(f, y, scale); }, ya, 1.0, kEps,
                          kInnerRelative);
}

}  // namespace snee::test
