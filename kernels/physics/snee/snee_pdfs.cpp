#include "kernels/physics/snee/snee_pdfs.h"

#include <cmath>

#include "kernels/physics/bsdf/fresnel.h"
#include "kernels/physics/medium/free_flight.h"
#include "kernels/physics/medium/henyey_greenstein.h"
#include "kernels/physics/snee/distance_samplers.h"
#include "kernels/physics/snee/joint_importance.h"
#include "kernels/physics/snee/manifold_sphere.h"
#include "kernels/physics/snee/probe.h"

namespace snee {

namespace {

// Density of the tracer's BSDF sampler at x_k choosing omega_o given omega_kj, in the measure
// left after the interface delta (solid angle when rough, a lobe probability when smooth).
double exit_bsdf_pdf(const SneeSuffix& s, const SuffixGeometry& g) {
  if (s.light_delta || !g.crosses) return 0.0;
  if (s.interface.delta()) return smooth_transmission_probability(s);
  return dielectric_pdf(s.interface, g.local_kj, g.local_o);
}

// Density of the tracer's light sampler at x_k in the same measure; a smooth interface can never
// transmit toward a sampled light direction.
double exit_light_pdf(const SneeSuffix& s, const SuffixGeometry& g) {
  if (s.interface.delta() || !g.crosses) return 0.0;
  return s.light_pdf;
}

// The walk's first step x_i -> x_j: phase sampling and a collision at x_j (volume measure).
double first_step_pdf(const SneeSuffix& s, const SuffixGeometry& g) {
  return hg_phase(dot(s.omega_in, g.omega_ij), s.medium.g) *
         free_flight_pdf(s.medium.sigma_t, static_cast<float>(g.r_ij)) / (g.r_ij * g.r_ij);
}

// The manifold strategy's part at x_j, in case D's measure dA(x_k) dt: it runs (its rate),
// takes the light (selection probability) and every exit point, so x_j's volume density becomes
// dA dt by the refraction volume Jacobian (docs/method.md 3.10). Zero wherever it does not run.
double manifold_exit_pdf(const SneeSuffix& s, const SuffixGeometry& g) {
  if (!s.manifold || !s.x_j_medium || !s.light_delta || !s.light_distant || !s.interface.delta() ||
      !(g.r_jk > 0) || !g.crosses) {
    return 0.0;
  }
  return s.manifold_rate * s.light_pdf *
         refraction_volume_jacobian(s.n_k, s.omega_o, s.interface.eta, s.boundary_curvature,
                                    g.r_jk);
}

double walk_pdf(const SneeSuffix& s, const SuffixGeometry& g) {
  if (!g.valid || !(g.cos_k_j > 0)) return 0.0;
  const float g_phase = s.medium.g;
  const double first = first_step_pdf(s, g);
  const double second = hg_phase(dot(g.omega_ij, g.omega_jk), g_phase) *
                        free_flight_survival(s.medium.sigma_t, static_cast<float>(g.r_jk)) *
                        g.cos_k_j / (g.r_jk * g.r_jk);
  return first * second;
}

double distance_pdf(const SneeSuffix& s, const SuffixGeometry& g, const SneeOptions& options) {
  const DistanceMixture m{s.medium.sigma_t, options.c_exponential, s.x_k, -g.omega_jk, s.x_i};
  return distance_mixture_pdf(m, static_cast<float>(g.r_jk));
}

double tb_pdf(const SneeSuffix& s, const SuffixGeometry& g, const SneeOptions& options) {
  if (!snee_can_produce(s) || !g.valid || !g.crosses) return 0.0;
  const double probe_and_light = probe_pdf(s, options) * s.light_pdf;
  const double t = g.r_jk;
  switch (suffix_measure(s)) {
    case SuffixMeasure::kFull:
    case SuffixMeasure::kDeltaLight:
      return probe_and_light * dielectric_transmission_pdf(s.interface, g.local_o, g.local_kj) *
             distance_pdf(s, g, options) / (t * t);
    case SuffixMeasure::kDeltaInterface: {
      // The refracted direction is deterministic; its solid angle relates to omega_o's by the
      // refraction Jacobian eta^2 cos_kj / cos_o (eta_a^2 cos_a dsigma_a = eta_b^2 cos_b dsigma_b).
      const double eta = s.interface.eta;
      const double jacobian = eta * eta * g.cos_k_j_shading / g.cos_o;
      return probe_and_light * jacobian * distance_pdf(s, g, options) / (t * t);
    }
    case SuffixMeasure::kDeltaBoth:
      return probe_and_light * distance_pdf(s, g, options);
  }
  return 0.0;
}

double bt_pdf(const SneeSuffix& s, const SuffixGeometry& g, const SneeOptions& options) {
  if (!snee_can_produce(s) || !g.valid || s.light_delta || !s.light_distant || !g.crosses) {
    return 0.0;
  }
  const JointImportance jis{s.x_i, s.omega_in, s.x_k, s.medium.g, options.c_joint};
  const double placement = probe_pdf(s, options) * joint_importance_pdf(jis, s.x_j);
  if (s.interface.delta()) return placement;  // transmission forced, refraction deterministic
  return placement * dielectric_transmission_pdf(s.interface, g.local_kj, g.local_o);
}

double heuristic(double p, MisHeuristic h) {
  return h == MisHeuristic::kPower ? p * p : p;
}

// The strategies that do not start from a probe, and so compete for suffixes SNEE's probe
// cannot produce.
bool is_walk_based(Strategy st) {
  return st == Strategy::kUnidirectionalBsdf || st == Strategy::kUnidirectionalLight ||
         st == Strategy::kManifold;
}

}  // namespace

double smooth_transmission_probability(const SneeSuffix& s) {
  // Evaluated from the inside, as the tracer's sampler does (same value up to rounding as from
  // the outside: Fresnel reflectance is symmetric over a refraction pair).
  const float cos_kj = dot(s.ns_k, normalize(s.x_k - s.x_j));
  if (!(cos_kj > 0)) return 0.0;
  return 1.0 - fresnel_dielectric(cos_kj, 1.0f / s.interface.eta);
}

double probe_pdf(const SneeSuffix& s, const SneeOptions& options) {
  if (!s.v_first) return 0.0;
  return probe_area_pdf(options.probe, s.omega_in, s.medium.g, s.x_i, s.x_k, s.n_k);
}

double unidirectional_walk_pdf(const SneeSuffix& s) {
  return walk_pdf(s, suffix_geometry(s));
}

double top_to_bottom_pdf(const SneeSuffix& s, const SneeOptions& options) {
  return tb_pdf(s, suffix_geometry(s), options);
}

double bottom_to_top_pdf(const SneeSuffix& s, const SneeOptions& options) {
  return bt_pdf(s, suffix_geometry(s), options);
}

double unidirectional_bsdf_pdf(const SneeSuffix& s) {
  const SuffixGeometry g = suffix_geometry(s);
  return walk_pdf(s, g) * exit_bsdf_pdf(s, g);
}

double manifold_pdf(const SneeSuffix& s) {
  const SuffixGeometry g = suffix_geometry(s);
  if (!g.valid) return 0.0;
  const double manifold = manifold_exit_pdf(s, g);
  return manifold > 0 ? first_step_pdf(s, g) * manifold : 0.0;
}

double unidirectional_light_pdf(const SneeSuffix& s) {
  const SuffixGeometry g = suffix_geometry(s);
  return walk_pdf(s, g) * exit_light_pdf(s, g);
}

StrategyPdfs strategy_pdfs(const SneeSuffix& s, const SneeOptions& options) {
  return strategy_pdfs(s, suffix_geometry(s), options);
}

StrategyPdfs strategy_pdfs(const SneeSuffix& s, const SuffixGeometry& g,
                           const SneeOptions& options) {
  StrategyPdfs out;
  out.handled = snee_can_produce(s);
  const auto set = [&](Strategy st, double p) { out.pdf[static_cast<int>(st)] = p; };
  if (!out.handled) {
    set(Strategy::kUnidirectionalBsdf, exit_bsdf_pdf(s, g));
    set(Strategy::kUnidirectionalLight, exit_light_pdf(s, g));
    set(Strategy::kManifold, manifold_exit_pdf(s, g));
    return out;
  }
  const double walk = walk_pdf(s, g);
  set(Strategy::kTopToBottom, tb_pdf(s, g, options));
  set(Strategy::kBottomToTop, bt_pdf(s, g, options));
  set(Strategy::kUnidirectionalBsdf, walk * exit_bsdf_pdf(s, g));
  set(Strategy::kUnidirectionalLight, walk * exit_light_pdf(s, g));
  const double manifold = manifold_exit_pdf(s, g);
  set(Strategy::kManifold, manifold > 0 ? first_step_pdf(s, g) * manifold : 0.0);
  return out;
}

double mis_weight(Strategy st, const StrategyPdfs& pdfs, const SneeOptions& options) {
  const auto competes = [&](Strategy t) {
    return pdfs.handled ? options.enabled.contains(t) : is_walk_based(t);
  };
  if (!competes(st) || !(pdfs[st] > 0)) return 0.0;
  double sum = 0;
  int infinite = 0;
  for (int i = 0; i < kStrategyCount; ++i) {
    const Strategy t = static_cast<Strategy>(i);
    if (!competes(t)) continue;
    const double h = heuristic(pdfs[t], options.heuristic);
    sum += h;
    infinite += std::isinf(h);
  }
  // A vertex on the point it connects to (within the ray clearance) makes a 1/r^2 pdf
  // infinite; the weights' limit shares the sample among the infinite ones (inf / inf would
  // be NaN and drop the whole sample).
  if (infinite > 0)
    return std::isinf(heuristic(pdfs[st], options.heuristic)) ? 1.0 / infinite : 0.0;
  return heuristic(pdfs[st], options.heuristic) / sum;
}

}  // namespace snee
