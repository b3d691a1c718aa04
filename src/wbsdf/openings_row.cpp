// Openings::rowMasses: a table row of cell masses (microstructure.h) in one sweep along u.
//
// On a piece of [x1, x2] between breakpoints, cellMass integrates f(u) = Δ·W(mid, u)·sinc(2uΔ) over each
// cell by Gauss–Legendre panels, Δ the piece's width (microstructure.cpp). With W's pair terms
// len·cos(2πuc)·sinc(u·len) = [sin(πu(len + 2c)) + sin(πu(len − 2c))]/(2πu),
//   f(u) = S(u)·sin(2πuΔ)/(4π²u²),  S(u) = Σ_q sin(πu·b_q),  b_q = len ± 2c over the piece's pairs,
// and f(0) = Δ·Σ len. The panel count depends only on the piece and du, so the panels of a whole row are
// evenly spaced in u: the sines and cosines of πb_q at one panel centre give the next centre's by one
// rotation, and a node's value by one more (with the node offsets' cosines and sines, tabulated once per
// piece). So a node costs two multiply-adds per frequency instead of two transcendental calls per pair.
// The rotation is reseeded from exact values every kReseed panels (its rounding grows linearly).
#include <algorithm>
#include <cmath>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/core/math.h"
#include "diffray/wbsdf/microstructure.h"

namespace diffray::wbsdf {

namespace {
constexpr int kOrder = 6;     // Gauss–Legendre nodes per panel, as cellMass
constexpr long kReseed = 16;  // panels between exact evaluations of the rotation's state
}  // namespace

void Openings::rowMasses(double x1, double x2, double u_first, double du, int count, double* out) const {
  DIFFRAY_CHECK(x2 > x1 && du > 0.0 && count >= 0);
  std::fill(out, out + count, 0.0);
  const core::GaussLegendre& gl = core::gaussLegendre(kOrder);
  std::vector<double> b, step_c, step_s, node_c, node_s, s, c;
  auto next = std::upper_bound(breakpoints_.begin(), breakpoints_.end(), x1);
  for (double lo = x1; lo < x2;) {
    double hi = x2;
    if (next != breakpoints_.end() && *next < x2) hi = *next++;
    const double width = hi - lo, mid = 0.5 * (lo + hi);
    lo = hi;
    const int panels = panelsFor(mid, width, du);
    const auto piece = static_cast<std::size_t>(
        std::upper_bound(breakpoints_.begin(), breakpoints_.end(), mid) - breakpoints_.begin());
    // The frequencies b_q of S (as pieceWdf's pairs), then 2Δ for the x-average's sine (the last one).
    b.clear();
    double sum_len = 0.0;
    for (std::size_t a = active_begin_[piece]; a < active_begin_[piece + 1]; ++a) {
      const auto [len, centre] = pairLag(active_pairs_[a], mid);
      if (!(len > 0.0)) continue;
      b.push_back(len + 2.0 * centre);
      b.push_back(len - 2.0 * centre);
      sum_len += len;
    }
    if (b.empty()) continue;  // no pair reaches this piece: W = 0
    const std::size_t nq = b.size();  // sines summed into S
    b.push_back(2.0 * width);
    const std::size_t nb = b.size();
    const double h = du / panels, half = 0.5 * h;
    step_c.resize(nb), step_s.resize(nb), s.resize(nb), c.resize(nb);
    node_c.resize(nb * kOrder), node_s.resize(nb * kOrder);
    for (std::size_t q = 0; q < nb; ++q) {
      step_c[q] = std::cos(core::kPi * b[q] * h);
      step_s[q] = std::sin(core::kPi * b[q] * h);
      for (int i = 0; i < kOrder; ++i) {
        node_c[i * nb + q] = std::cos(core::kPi * b[q] * half * gl.nodes[i]);
        node_s[i * nb + q] = std::sin(core::kPi * b[q] * half * gl.nodes[i]);
      }
    }
    const double scale = 1.0 / (x2 - x1);
    for (int k = 0; k < count; ++k) {
      double cell = 0.0;
      for (int p = 0; p < panels; ++p) {
        const double centre = u_first + k * du + (p + 0.5) * h;
        if ((static_cast<long>(k) * panels + p) % kReseed == 0) {
          for (std::size_t q = 0; q < nb; ++q) {
            s[q] = std::sin(core::kPi * b[q] * centre);
            c[q] = std::cos(core::kPi * b[q] * centre);
          }
        }
        double sum = 0.0;
        for (int i = 0; i < kOrder; ++i) {
          const double* nc = &node_c[i * nb];
          const double* ns = &node_s[i * nb];
          double S = 0.0;
          for (std::size_t q = 0; q < nq; ++q) S += s[q] * nc[q] + c[q] * ns[q];
          const double sine = s[nq] * nc[nq] + c[nq] * ns[nq];  // sin(2πuΔ)
          const double u = centre + half * gl.nodes[i];
          const double f = u != 0.0 ? S * sine / (4.0 * core::kPi * core::kPi * u * u) : width * sum_len;
          sum += gl.weights[i] * f;
        }
        cell += half * sum;
        for (std::size_t q = 0; q < nb; ++q) {  // to the next panel's centre
          const double sq = s[q] * step_c[q] + c[q] * step_s[q];
          c[q] = c[q] * step_c[q] - s[q] * step_s[q];
          s[q] = sq;
        }
      }
      out[k] += cell * scale;
    }
  }
}

}  // namespace diffray::wbsdf
