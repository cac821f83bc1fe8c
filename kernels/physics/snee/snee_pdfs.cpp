#include "kernels/physics/snee/snee_pdfs.h"

#include "kernels/physics/snee/manifold_sphere.h"

namespace snee {

namespace {

SuffixLanes<double> in_double(const SneeSuffix& s) {
  return {Vec3d(s.x_i),
          Vec3d(s.omega_in),
          Vec3d(s.x_j),
          Vec3d(s.x_k),
          Vec3d(s.n_k),
          Vec3d(s.ns_k),
          Vec3d(s.omega_o),
          Vec3d(s.medium.sigma_s),
          Vec3d(s.medium.sigma_t),
          s.medium.g,
          s.interface.as<double>(),
          s.light_pdf,
          s.light_delta,
          s.light_distant};
}

// The manifold strategy's part at x_j, in case D's measure dA(x_k) dt: it runs (its rate),
// takes the light (selection probability) and every exit point, so x_j's volume density becomes
// dA dt by the refraction volume Jacobian (docs/method.md 3.10). Zero wherever it does not run.
double manifold_exit_pdf(const SneeSuffix& s, const SuffixWeighing<double>& w) {
  if (!s.manifold || !s.x_j_medium || !s.light_delta || !s.interface.delta() || !(w.r_jk > 0) ||
      !w.crosses) {
    return 0.0;
  }
  return s.manifold_rate * s.light_pdf *
         refraction_volume_jacobian(s.n_k, s.omega_o, s.interface.eta, s.boundary_curvature, w.r_jk,
                                    s.manifold_light_distance);
}

// The manifold strategy from x_j's walk step on, for suffixes whose x_i is a medium vertex.
double manifold_walk_pdf(const SneeSuffix& s, const SuffixWeighing<double>& w) {
  const double manifold = manifold_exit_pdf(s, w);
  return manifold > 0 && w.valid ? w.first_step * manifold : 0.0;
}

// The strategies that do not start from a probe, and so compete for suffixes SNEE's probe
// cannot produce.
bool is_walk_based(Strategy st) {
  return st == Strategy::kUnidirectionalBsdf || st == Strategy::kUnidirectionalLight ||
         st == Strategy::kManifold;
}

}  // namespace

SuffixWeighing<double> weigh_suffix(const SneeSuffix& s, const SneeOptions& options) {
  return weigh_suffix<double>(in_double(s), options);
}

double top_to_bottom_pdf(const SneeSuffix& s, const SneeOptions& options) {
  return snee_can_produce(s)
             ? weigh_suffix(s, options).pdf[static_cast<int>(Strategy::kTopToBottom)]
             : 0.0;
}

double bottom_to_top_pdf(const SneeSuffix& s, const SneeOptions& options) {
  return snee_can_produce(s)
             ? weigh_suffix(s, options).pdf[static_cast<int>(Strategy::kBottomToTop)]
             : 0.0;
}

double manifold_pdf(const SneeSuffix& s) {
  return manifold_walk_pdf(s, weigh_suffix(s, SneeOptions{}));
}

StrategyPdfs strategy_pdfs(const SneeSuffix& s, const SneeOptions& options) {
  return strategy_pdfs(s, weigh_suffix(s, options));
}

StrategyPdfs strategy_pdfs(const SneeSuffix& s, const SuffixWeighing<double>& w) {
  StrategyPdfs out;
  out.handled = snee_can_produce(s);
  const auto set = [&](Strategy st, double p) { out.pdf[static_cast<int>(st)] = p; };
  if (!out.handled) {
    set(Strategy::kUnidirectionalBsdf, !s.light_delta && w.crosses ? w.exit_bsdf : 0.0);
    set(Strategy::kUnidirectionalLight, !s.interface.delta() && w.crosses ? s.light_pdf : 0.0);
    set(Strategy::kManifold, manifold_exit_pdf(s, w));
    return out;
  }
  out.pdf = w.pdf;
  set(Strategy::kManifold, manifold_walk_pdf(s, w));
  return out;
}

double mis_weight(Strategy st, const StrategyPdfs& pdfs, const SneeOptions& options) {
  MisWeights<double>::Competing competing;
  for (int t = 0; t < kStrategyCount; ++t) {
    const Strategy strategy = static_cast<Strategy>(t);
    competing[t] = pdfs.handled ? options.enabled.contains(strategy) : is_walk_based(strategy);
  }
  return MisWeights<double>(pdfs.pdf, competing, options.heuristic)(st);
}

}  // namespace snee
