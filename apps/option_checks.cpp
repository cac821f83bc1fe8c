#include "apps/option_checks.h"

#include <tbb/info.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <sstream>

#include "scheduler/render.h"

namespace snee {
namespace {

std::string number_text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

// strtod, not from_chars: it reads what CLI11 reads ("1e-3", "0x1p-2", "inf", "nan"), so the
// check sees the value the option will get.
CLI::Validator finite_number(const std::string& expected, const std::function<bool(double)>& ok) {
  return CLI::Validator(
      [expected, ok](const std::string& text) {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        return !text.empty() && end == text.c_str() + text.size() && std::isfinite(value) &&
                       ok(value)
                   ? std::string()
                   : "expected " + expected + ", got '" + text + "'";
      },
      "NUMBER");
}

}  // namespace

CLI::Validator finite_in_range(double min, double max) {
  return finite_number("a finite number from " + number_text(min) + " to " + number_text(max),
                       [min, max](double x) { return x >= min && x <= max; });
}

CLI::Validator finite_at_least(double min) {
  return finite_number("a finite number of at least " + number_text(min),
                       [min](double x) { return x >= min; });
}

CLI::Validator finite_positive() {
  return finite_number("a finite number above 0", [](double x) { return x > 0; });
}

int capped_threads(int requested, const char* option) {
  const int limit = max_render_threads();
  if (requested <= limit) return requested;
  std::fprintf(stderr,
               "warning: %s %d is more than the limit of %d (%d per hardware thread, %d here); "
               "using %d\n",
               option, requested, limit, kMaxThreadsPerHardwareThread,
               tbb::info::default_concurrency(), limit);
  return limit;
}

}  // namespace snee
