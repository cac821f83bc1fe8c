// One density function per strategy that can produce a SNEE suffix (docs/method.md 3.3-3.7), and
// the multi-sample MIS weights built from them. Every place that weights a suffix (the
// subdivision strategies and the tracer's exit events) calls these, so the weights of the
// strategies that can produce a path always sum to one (docs/method.md 3.6, correctness rule).
//
// All path densities are in the measure of suffix_measure(s) (cases A-D) and are 0 wherever the
// strategy cannot produce the suffix; in particular the probe-based ones are 0 unless
// snee_can_produce(s).
#pragma once

#include <array>

#include "kernels/physics/snee/snee_options.h"
#include "kernels/physics/snee/snee_suffix.h"

namespace snee {

// Area density of the probe reaching x_k from x_i, including V_first(x_i, x_k).
double probe_pdf(const SneeSuffix& s, const SneeOptions& options);
// The tracer's random walk x_i -> x_j -> x_k: phase sampling and a free flight that collides at
// x_j (volume measure), then phase sampling and a flight that passes the boundary distance
// (area measure at x_k). Only meaningful when x_i and x_j are medium vertices.
double unidirectional_walk_pdf(const SneeSuffix& s);

double top_to_bottom_pdf(const SneeSuffix& s, const SneeOptions& options);
double bottom_to_top_pdf(const SneeSuffix& s, const SneeOptions& options);
double unidirectional_bsdf_pdf(const SneeSuffix& s);
double unidirectional_light_pdf(const SneeSuffix& s);
// The manifold strategy at x_j (docs/method.md 3.10), in case D's measure dA(x_k) dt: the walk's
// step to x_j, the light's selection probability and the refraction volume Jacobian. Only
// meaningful when x_i and x_j are medium vertices; 0 unless s.manifold.
double manifold_pdf(const SneeSuffix& s);

// The tracer's probability of choosing transmission at a smooth interface when refracting from
// the inside at x_k: its Fresnel-proportional lobe choice (dielectric_sample's delta pdf).
double smooth_transmission_probability(const SneeSuffix& s);

struct StrategyPdfs {
  std::array<double, kStrategyCount> pdf{};  // indexed by Strategy
  // Whether the probe-based strategies can produce the suffix. If not, only the tracer's two
  // strategies compete and `pdf` holds their densities at the exit vertex alone (the common walk
  // density cancels, and is undefined when x_i or x_j is a surface vertex).
  bool handled = false;
  double operator[](Strategy st) const { return pdf[static_cast<int>(st)]; }
};
StrategyPdfs strategy_pdfs(const SneeSuffix& s, const SneeOptions& options);
// The same with the suffix's geometry already derived (suffix_geometry(s)).
StrategyPdfs strategy_pdfs(const SneeSuffix& s, const SuffixGeometry& g,
                           const SneeOptions& options);

// Weight of strategy st for the suffix the pdfs describe: balance or power heuristic over the
// strategies that compete for it (the enabled ones for handled suffixes, U_B, U_L and the
// manifold strategy otherwise);
// 0 when st does not compete or cannot produce the suffix.
double mis_weight(Strategy st, const StrategyPdfs& pdfs, const SneeOptions& options);

}  // namespace snee
