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
constexpr long kReseed = 16;  // panels between exact evaluations of the rotation's state
}  // namespace

void Openings::rowMasses(double x1, double x2, double u_first, double du, int count, double* out) const {
  DIFFRAY_CHECK(x2 > x1 && du > 0.0 && count >= 0);
  std::fill(out, out + count, 0.0);
  if (count == 0) return;
  constexpr int kNodes = kCellNodes;
  const core::GaussLegendre& gl = core::gaussLegendre(kNodes);
  const double scale = 1.0 / (x2 - x1);
  std::vector<std::pair<double, double>> terms;  // (|b|, ±1) of each sine of S
  std::vector<double> b, weight, step_c, step_s, node_c, node_s, s, c;
  forEachPiece(x1, x2, [&](double width, double mid, std::size_t piece) {
    const int panels = panelsFor(mid, width, du);
    // S's sines, sin(πu·b) = sign(b)·sin(πu·|b|): the ordered pairs (j, k) and (k, j) give the same two
    // frequencies, so equal |b| are merged into one frequency with the sum of their signs as its weight.
    terms.clear();
    double sum_len = 0.0;
    for (std::size_t a = active_begin_[piece]; a < active_begin_[piece + 1]; ++a) {
      const auto [len, centre] = pairLag(active_pairs_[a], mid);
      if (!(len > 0.0)) continue;
      sum_len += len;
      for (const double f : {len + 2.0 * centre, len - 2.0 * centre})
        if (f != 0.0) terms.emplace_back(std::abs(f), f > 0.0 ? 1.0 : -1.0);
    }
    if (!(sum_len > 0.0)) return;  // no pair reaches this piece: W = 0
    std::sort(terms.begin(), terms.end());
    b.clear();
    weight.clear();
    for (const auto& [f, sign] : terms) {
      if (!b.empty() && b.back() == f) weight.back() += sign;
      else b.push_back(f), weight.push_back(sign);
    }
    const std::size_t nq = b.size();  // S's frequencies; then 2Δ for the x-average's sine (the last one)
    b.push_back(2.0 * width);
    weight.push_back(1.0);
    const std::size_t nb = b.size();
    const double h = du / panels, half = 0.5 * h;
    step_c.resize(nb), step_s.resize(nb), s.resize(nb), c.resize(nb);
    node_c.resize(nb * kNodes), node_s.resize(nb * kNodes);
    for (std::size_t q = 0; q < nb; ++q) {
      step_c[q] = std::cos(core::kPi * b[q] * h);
      step_s[q] = std::sin(core::kPi * b[q] * h);
      for (int i = 0; i < kNodes; ++i) {  // node offsets, weights folded in
        node_c[q * kNodes + i] = weight[q] * std::cos(core::kPi * b[q] * half * gl.nodes[i]);
        node_s[q * kNodes + i] = weight[q] * std::sin(core::kPi * b[q] * half * gl.nodes[i]);
      }
    }
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
        // S at the panel's nodes: one accumulator per node (independent chains, in q order).
        double S[kNodes] = {};
        for (std::size_t q = 0; q < nq; ++q) {
          const double* nc = &node_c[q * kNodes];
          const double* ns = &node_s[q * kNodes];
          for (int i = 0; i < kNodes; ++i) S[i] += s[q] * nc[i] + c[q] * ns[i];
        }
        double sum = 0.0;
        for (int i = 0; i < kNodes; ++i) {
          const double sine = s[nq] * node_c[nq * kNodes + i] + c[nq] * node_s[nq * kNodes + i];  // sin(2πuΔ)
          const double u = centre + half * gl.nodes[i];
          const double f = u != 0.0 ? S[i] * sine / (4.0 * core::kPi * core::kPi * u * u) : width * sum_len;
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
  });
}

}  // namespace diffray::wbsdf
