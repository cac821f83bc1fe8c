// The densities of the strategies that can produce a SNEE suffix (docs/method.md 3.3-3.7), and
// the multi-sample MIS weights built from them: suffix_weighing.h's templates in double, plus the
// manifold strategy and the suffixes SNEE cannot produce, which only the scalar code meets. Every
// place that weights a suffix (the subdivision strategies and the tracer's exit events) calls
// these, so the weights of the strategies that can produce a path always sum to one
// (docs/method.md 3.6, correctness rule).
//
// All path densities are in the suffix's measure (cases A-D, suffix_weighing.h) and are 0 wherever
// the strategy cannot produce the suffix; in particular the probe-based ones are 0 unless
// snee_can_produce(s).
#pragma once

#include <array>

#include "core/vec3d.h"
#include "kernels/physics/snee/snee_options.h"
#include "kernels/physics/snee/snee_suffix.h"
#include "kernels/physics/snee/suffix_weighing.h"

namespace snee {

// weigh_suffix over one suffix, in double.
SuffixWeighing<double> weigh_suffix(const SneeSuffix& s, const SneeOptions& options);

double top_to_bottom_pdf(const SneeSuffix& s, const SneeOptions& options);
double bottom_to_top_pdf(const SneeSuffix& s, const SneeOptions& options);
// The manifold strategy at x_j (docs/method.md 3.10), in case D's measure dA(x_k) dt: the walk's
// step to x_j, its rate, the light's selection probability and the refraction volume Jacobian.
// Only meaningful when x_i and x_j are medium vertices; 0 unless s.manifold.
double manifold_pdf(const SneeSuffix& s);

struct StrategyPdfs {
  std::array<double, kStrategyCount> pdf{};  // indexed by Strategy
  // Whether the probe-based strategies can produce the suffix. If not, only the tracer's
  // strategies (and the manifold strategy) compete and `pdf` holds their densities at the exit
  // vertex alone (the common walk density cancels, and is undefined when x_i or x_j is a
  // surface vertex).
  bool handled = false;
  double operator[](Strategy st) const { return pdf[static_cast<int>(st)]; }
};
StrategyPdfs strategy_pdfs(const SneeSuffix& s, const SneeOptions& options);
// The same from the suffix already weighed (weigh_suffix(s, options)).
StrategyPdfs strategy_pdfs(const SneeSuffix& s, const SuffixWeighing<double>& w);

// Weight of strategy st for the suffix the pdfs describe: balance or power heuristic over the
// strategies that compete for it (the enabled ones for handled suffixes, U_B, U_L and the
// manifold strategy otherwise); 0 when st does not compete or cannot produce the suffix.
double mis_weight(Strategy st, const StrategyPdfs& pdfs, const SneeOptions& options);

}  // namespace snee
