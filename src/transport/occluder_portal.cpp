// The portal scattering of a ray that carries every band (RoomOccluders::scatterPortal): one outgoing
// direction for all bands, drawn from one band's law, each band weighted by its own law over the mixture of
// all bands' proposals (one-sample multiple importance sampling with the balance heuristic, Veach 1997,
// thesis §9.2.4): E[f_i/q] = ∫f_i for every band i, wherever q = (1/n)Σ_j q_j covers f_i.
#include <algorithm>
#include <cmath>

#include "diffray/core/error.h"
#include "diffray/transport/room_occluders.h"
#include "diffray/wbsdf/edge_kernel.h"
#include "diffray/wbsdf/far_field.h"

namespace diffray::transport {

using core::Vec3;
using Kind = room::OccluderAxis::Kind;

// One axis's law of the outgoing direction cosine c' = c + λu' (paper eq. 8) for a band of wavelength λ, per
// unit of c': the opening's far-field pattern (wbsdf/far_field.h, length = its width, doubled by a mirror) or
// the edge kernel (wbsdf/edge_kernel.h, length = 4d), in w = (c' − c)·length/λ; only |c'| < c_max propagates.
struct RoomOccluders::AxisLaw {
  Kind kind = Kind::Uniform;
  double length = 0.0, c = 0.0, c_max = 1.0, open_sign = 0.0;

  double scale(double lambda_m) const { return length / lambda_m; }
  double lo(double lambda_m) const { return (-c_max - c) * scale(lambda_m); }
  double hi(double lambda_m) const { return (c_max - c) * scale(lambda_m); }
  // The edge kernel's range holds 0 (wbsdf/edge_kernel.h: w_lo ≤ 0 ≤ w_hi).
  double edgeLo(double lambda_m) const { return std::min(0.0, lo(lambda_m)); }
  double edgeHi(double lambda_m) const { return std::max(0.0, hi(lambda_m)); }
  /// The target density (what the band's estimate integrates): W's or the far-field pattern's, 0 where
  /// evanescent.
  double target(double cp, double lambda_m) const {
    if (!(std::abs(cp) < c_max)) return 0.0;
    const double s = scale(lambda_m), w = (cp - c) * s;
    return s * (kind == Kind::Opening ? wbsdf::farFieldEval(w) : wbsdf::edgeKernelEval(w));
  }
  /// The proposal's density (what the band's sampler draws from).
  double proposal(double cp, double lambda_m) const {
    const double s = scale(lambda_m), w = (cp - c) * s;
    return s * (kind == Kind::Opening ? wbsdf::farFieldPdf(w, lo(lambda_m), hi(lambda_m))
                                      : wbsdf::edgeKernelPdf(w, edgeLo(lambda_m), edgeHi(lambda_m)));
  }
  /// Draws c' from the band's proposal; false when its range is empty.
  bool sample(double lambda_m, const double* xi, double& cp) const {
    const double s = scale(lambda_m);
    double w;
    if (kind == Kind::Opening) {
      const wbsdf::FarFieldSample f = wbsdf::farFieldSample(lo(lambda_m), hi(lambda_m), xi[0]);
      if (f.weight == 0.0) return false;
      w = f.w;
    } else {
      w = wbsdf::edgeKernelSample(edgeLo(lambda_m), edgeHi(lambda_m), xi[0], xi[1]).w;
    }
    cp = c + w / s;
    return true;
  }
};

RoomOccluders::AxisLaw RoomOccluders::axisLaw(const Axis& a, double coord, double c, double c_max) {
  AxisLaw law;
  law.kind = a.spec.kind;
  law.c = c;
  law.c_max = c_max;
  if (law.kind == Kind::Opening || law.kind == Kind::Edge) {
    double four_d;
    edgeDistance(a, coord, four_d, law.open_sign);
    law.length = law.kind == Kind::Edge ? four_d : (a.spec.mirror_lo ? 2.0 : 1.0) * (a.spec.hi_m - a.spec.lo_m);
  }
  return law;
}

RoomOccluders::PortalScatter RoomOccluders::scatterPortal(int k, const Vec3& p, const Vec3& dir, const double* lambda_m,
                                                          int n, int pick, const double xi[4], double* weight) const {
  DIFFRAY_CHECK(nextEventSupported(k) && n > 0 && pick >= 0 && pick < n);
  const Entry& e = occluders_[k];
  const room::Occluder& o = e.spec;
  const Vec3 local = p - o.origin_m;
  const double alpha_i = dir.dot(o.ex), beta_i = dir.dot(o.ey);
  PortalScatter s;
  std::fill(weight, weight + n, 0.0);
  // As scatter(): the x axis first, within |α'| < √(1 − β²) when y does not diffract, then y within
  // |β'| < √(1 − α'²).
  const bool y_uniform = e.y.spec.kind == Kind::Uniform, x_uniform = e.x.spec.kind == Kind::Uniform;
  const AxisLaw lx = axisLaw(e.x, local.dot(o.ex), alpha_i, y_uniform ? std::sqrt(std::max(0.0, 1.0 - beta_i * beta_i)) : 1.0);
  double alpha = alpha_i;
  if (!x_uniform && !lx.sample(lambda_m[pick], xi, alpha)) return s;
  const AxisLaw ly = axisLaw(e.y, local.dot(o.ey), beta_i, std::sqrt(std::max(0.0, 1.0 - alpha * alpha)));
  double beta = beta_i;
  if (!y_uniform && !ly.sample(lambda_m[pick], xi + 2, beta)) return s;
  const double gamma_sq = 1.0 - alpha * alpha - beta * beta;
  if (!(gamma_sq > 0.0)) {
    s.evanescent = true;
    return s;
  }
  // Each band's target over the mixture of the bands' proposals (a uniform axis is the same for every band:
  // it cancels).
  double mixture = 0.0;
  for (int i = 0; i < n; ++i)
    mixture += (x_uniform ? 1.0 : lx.proposal(alpha, lambda_m[i])) * (y_uniform ? 1.0 : ly.proposal(beta, lambda_m[i]));
  mixture /= n;
  if (!(mixture > 0.0)) return s;
  s.dir = alpha * o.ex + beta * o.ey + std::copysign(std::sqrt(gamma_sq), dir.dot(o.normal)) * o.normal;
  double faces = 1.0;
  if (lx.open_sign != 0.0) faces *= facesFactor(e.x.spec.faces, lx.open_sign * o.ex, o.normal, dir, s.dir);
  if (ly.open_sign != 0.0) faces *= facesFactor(e.y.spec.faces, ly.open_sign * o.ey, o.normal, dir, s.dir);
  bool any = false;
  for (int i = 0; i < n; ++i) {
    const double f = (x_uniform ? 1.0 : lx.target(alpha, lambda_m[i])) * (y_uniform ? 1.0 : ly.target(beta, lambda_m[i]));
    weight[i] = f / mixture * faces;
    any = any || weight[i] != 0.0;
  }
  if (!any) s.evanescent = true;  // an edge kernel's draw past the propagating range (its last partial period)
  s.alive = any;
  return s;
}

}  // namespace diffray::transport
