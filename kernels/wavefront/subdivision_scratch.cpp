#include "kernels/wavefront/subdivision_scratch.h"

#include <cassert>

namespace snee {

namespace {

void store(const Vec3& v, size_t i, AlignedArray<float>& x, AlignedArray<float>& y,
           AlignedArray<float>& z) {
  x[i] = v.x;
  y[i] = v.y;
  z[i] = v.z;
}

Vec3 load(size_t i, const AlignedArray<float>& x, const AlignedArray<float>& y,
          const AlignedArray<float>& z) {
  return {x[i], y[i], z[i]};
}

void store_segment(const ShadowSegment& seg, size_t i, AlignedArray<float>& ox,
                   AlignedArray<float>& oy, AlignedArray<float>& oz, AlignedArray<float>& dx,
                   AlignedArray<float>& dy, AlignedArray<float>& dz, AlignedArray<float>& t) {
  store(seg.origin, i, ox, oy, oz);
  store(seg.direction, i, dx, dy, dz);
  t[i] = seg.t_max;
}

}  // namespace

void ProposalQueue::push(const SneeProposal& p, Strategy strategy, uint32_t slot) {
  assert(size_ < items_.slot.size());
  const size_t i = size_++;
  ProposalItems& q = items_;
  const SneeSuffix& s = p.suffix;
  q.slot[i] = slot;
  q.strategy[i] = static_cast<uint32_t>(strategy);
  store(s.x_i, i, q.xi_x, q.xi_y, q.xi_z);
  store(s.omega_in, i, q.win_x, q.win_y, q.win_z);
  store(s.x_j, i, q.xj_x, q.xj_y, q.xj_z);
  store(s.x_k, i, q.xk_x, q.xk_y, q.xk_z);
  store(s.n_k, i, q.nk_x, q.nk_y, q.nk_z);
  store(s.ns_k, i, q.snk_x, q.snk_y, q.snk_z);
  store(s.omega_o, i, q.wo_x, q.wo_y, q.wo_z);
  store(s.medium.sigma_s, i, q.sigma_s_x, q.sigma_s_y, q.sigma_s_z);
  store(s.medium.sigma_t, i, q.sigma_t_x, q.sigma_t_y, q.sigma_t_z);
  q.g[i] = s.medium.g;
  q.eta[i] = s.interface.eta;
  q.alpha[i] = s.interface.alpha;
  q.light_pdf[i] = s.light_pdf;
  q.light_delta[i] = s.light_delta ? 1.0f : 0.0f;
  q.light_distant[i] = s.light_distant ? 1.0f : 0.0f;
  q.manifold[i] = s.manifold ? 1u : 0u;
  q.manifold_rate[i] = s.manifold_rate;
  q.boundary_curvature[i] = s.boundary_curvature;
  q.manifold_light_distance[i] = s.manifold_light_distance;
  store(p.emitted, i, q.emitted_r, q.emitted_g, q.emitted_b);
  q.sampling_pdf[i] = p.sampling_pdf;
  store_segment(p.segments[0], i, q.o0_x, q.o0_y, q.o0_z, q.d0_x, q.d0_y, q.d0_z, q.t0);
  store_segment(p.segments[1], i, q.o1_x, q.o1_y, q.o1_z, q.d1_x, q.d1_y, q.d1_z, q.t1);
  store_segment(p.segments[2], i, q.o2_x, q.o2_y, q.o2_z, q.d2_x, q.d2_y, q.d2_z, q.t2);
}

std::array<ShadowSegment, 3> ProposalQueue::segments(size_t i) const {
  const ProposalItems& q = items_;
  return {ShadowSegment{load(i, q.o0_x, q.o0_y, q.o0_z), load(i, q.d0_x, q.d0_y, q.d0_z), q.t0[i]},
          ShadowSegment{load(i, q.o1_x, q.o1_y, q.o1_z), load(i, q.d1_x, q.d1_y, q.d1_z), q.t1[i]},
          ShadowSegment{load(i, q.o2_x, q.o2_y, q.o2_z), load(i, q.d2_x, q.d2_y, q.d2_z), q.t2[i]}};
}

SneeProposal ProposalQueue::proposal(size_t i) const {
  const ProposalItems& q = items_;
  SneeProposal p;
  SneeSuffix& s = p.suffix;
  s.x_i = load(i, q.xi_x, q.xi_y, q.xi_z);
  s.omega_in = load(i, q.win_x, q.win_y, q.win_z);
  s.x_j = load(i, q.xj_x, q.xj_y, q.xj_z);
  s.x_k = load(i, q.xk_x, q.xk_y, q.xk_z);
  s.n_k = load(i, q.nk_x, q.nk_y, q.nk_z);
  s.ns_k = load(i, q.snk_x, q.snk_y, q.snk_z);
  s.omega_o = load(i, q.wo_x, q.wo_y, q.wo_z);
  s.medium.sigma_s = load(i, q.sigma_s_x, q.sigma_s_y, q.sigma_s_z);
  s.medium.sigma_t = load(i, q.sigma_t_x, q.sigma_t_y, q.sigma_t_z);
  s.medium.g = q.g[i];
  s.interface = {q.eta[i], q.alpha[i]};
  s.light_pdf = q.light_pdf[i];
  s.light_delta = q.light_delta[i] != 0.0f;
  s.light_distant = q.light_distant[i] != 0.0f;
  s.v_first = s.x_i_medium = s.x_j_medium = true;
  s.manifold = q.manifold[i] != 0;
  s.manifold_rate = q.manifold_rate[i];
  s.boundary_curvature = q.boundary_curvature[i];
  s.manifold_light_distance = q.manifold_light_distance[i];
  p.emitted = load(i, q.emitted_r, q.emitted_g, q.emitted_b);
  p.sampling_pdf = q.sampling_pdf[i];
  p.segments = segments(i);
  p.failure = SneeFailure::kNone;
  return p;
}

}  // namespace snee
