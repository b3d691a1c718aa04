#pragma once
// Shared fixtures of the transport tests (transport_test.cpp, transport_energy_test.cpp): tiny hand-built
// tables, frames, and fate moments computed directly from table masses (an oracle independent of the
// tracer's sampling code).
#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "diffray/geometry/frame.h"
#include "diffray/receiver/screen.h"
#include "diffray/transport/tracer.h"
#include "diffray/wbsdf/table.h"

namespace diffray::testing {

namespace dw = diffray::wbsdf;
namespace dtr = diffray::transport;
namespace dg = diffray::geometry;
using diffray::core::Vec3;

/// A table with one row over [x_lo, x_hi] and a single line of mass 1 at u' = u_shift: W = δ(u − u_shift)
/// (|t|² = 1; u_shift = 0 is a fully open occluder). Outside the row the occluder is opaque.
inline std::shared_ptr<const dw::WbsdfTable> deltaTable(double x_lo, double x_hi, double u_shift) {
  dw::TableLayout L;
  L.x0_m = x_lo;
  L.dx_m = x_hi - x_lo;
  L.nx = 1;
  L.du_per_m = 1.0;
  L.u0_per_m = u_shift - 0.5;
  L.nu = 1;
  L.line_spectrum = true;
  return std::make_shared<const dw::WbsdfTable>(L, std::vector<double>{1.0});
}

inline dg::Frame frameAt(const Vec3& origin) {
  dg::Frame f;
  f.origin = origin;
  return f;  // axes x, y, z
}

inline double total(const diffray::receiver::ScreenTally& t) {
  double s = 0.0;
  for (double v : t.sum) s += v;
  return s;
}

inline double fates(const dtr::TraceResult& r) {
  double s = r.absorbed + r.evanescent + r.escaped + r.on_absorbers + r.bounce_limit;
  for (const auto& t : r.screens) s += total(t);
  return s;
}

inline dw::TableOptions optionsFor(double wavelength) {
  dw::TableOptions o;
  o.wavelength_m = wavelength;
  return o;
}

/// Length of [a1, a2] ∩ [b1, b2].
inline double overlap(double a1, double a2, double b1, double b2) { return std::max(0.0, std::min(a2, b2) - std::max(a1, b1)); }

/// Expectation and second moment, per emitted ray and in units of the ray's initial energy, of the signed
/// energy a ray brings to a fate, when the ray hits the occluder at x uniform on [w1, w2] and then ends in
/// that fate iff its sampled u' (uniform within the chosen cell of a continuous table, table.h) lies in the set where
/// `fraction(u1, u2)` gives the covered fraction of a cell. The ray's weight is sign(m_jk)·R_j with
/// probability |m_jk|/R_j, so per ray E[X] = Σ_j p_j Σ_k m_jk f_k and E[X²] = Σ_j p_j R_j Σ_k |m_jk| f_k,
/// p_j the fraction of the window in row j (rows outside the table: weight 0).
template <class Fraction>
std::pair<double, double> fateMoments(const dw::WbsdfTable& table, double w1, double w2, Fraction fraction) {
  const dw::TableLayout& L = table.layout();
  double mean = 0.0, second = 0.0;
  std::vector<double> f(L.nu);
  for (int k = 0; k < L.nu; ++k) {
    const double u1 = L.u0_per_m + k * L.du_per_m;
    f[k] = fraction(u1, u1 + L.du_per_m);
  }
  for (int j = 0; j < L.nx; ++j) {
    const double x1 = L.x0_m + j * L.dx_m;
    const double p = overlap(x1, x1 + L.dx_m, w1, w2) / (w2 - w1);
    if (p == 0.0) continue;
    double m = 0.0, a = 0.0, r = 0.0;
    for (int k = 0; k < L.nu; ++k) {
      m += table.mass(j, k) * f[k];
      a += std::abs(table.mass(j, k)) * f[k];
      r += std::abs(table.mass(j, k));
    }
    mean += p * m;
    second += p * r * a;
  }
  return {mean, second};
}


}  // namespace diffray::testing
