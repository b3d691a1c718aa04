#include "diffray/wbsdf/microstructure.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "diffray/core/error.h"
#include "diffray/core/math.h"

namespace diffray::wbsdf {

using core::kPi;
using core::sinc;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

// ---------------------------------------------------------------------------------------------------
// Openings. For openings j = [p_j, q_j] and k = [p_k, q_k] the cross-Wigner term of paper eq. 2 is
//   ∫ 1[x+s/2 ∈ j] 1[x−s/2 ∈ k] e^{−i2πus} ds = ∫_{s_lo}^{s_hi} e^{−i2πus} ds,
//   s_lo = max(2(p_j−x), 2(x−q_k)),  s_hi = min(2(q_j−x), 2(x−p_k)),
// and the (j,k) + (k,j) pair sums to a real L·cos(2πu s_c)·sinc(uL) per ordered pair, with
// L = s_hi − s_lo > 0 and s_c = (s_lo + s_hi)/2. A single slit gives the rect's closed form 2w·sinc(2uw), w = a−2|x|.
// Both s-limits are piecewise linear in x with slopes ±2, so between breakpoints the x-average over a
// piece of width Δ is exactly the midpoint value times sinc(2uΔ): this is what cellMass uses.
// ---------------------------------------------------------------------------------------------------

void Microstructure::rowMasses(double x1, double x2, double u_first, double du, int count, double* out) const {
  for (int k = 0; k < count; ++k) out[k] = cellMass(x1, x2, u_first + k * du, u_first + k * du + du);
}

Openings::Openings(std::vector<std::pair<double, double>> intervals_m) : intervals_(std::move(intervals_m)) {
  if (intervals_.empty()) throw core::InputError("openings", "at least one opening is needed");
  std::sort(intervals_.begin(), intervals_.end());
  for (std::size_t i = 0; i < intervals_.size(); ++i) {
    const auto& [p, q] = intervals_[i];
    core::requireFinite("opening start", p);
    if (!(q > p)) throw core::InputError("opening width", "must be > 0 (an opening [" + std::to_string(p) +
                                                              ", " + std::to_string(q) + "] m)");
    if (i > 0 && p < intervals_[i - 1].second)
      throw core::InputError("openings", "openings overlap; give each opening once");
  }
  for (const auto& [pj, qj] : intervals_)
    for (const auto& [pk, qk] : intervals_)
      for (double b : {0.5 * (pj + pk), 0.5 * (qj + qk), 0.5 * (pj + qk), 0.5 * (qj + pk)})
        if (std::isfinite(b)) breakpoints_.push_back(b);
  std::sort(breakpoints_.begin(), breakpoints_.end());
  breakpoints_.erase(std::unique(breakpoints_.begin(), breakpoints_.end()), breakpoints_.end());
  // Pair (j,k) is non-zero exactly for (p_j+p_k)/2 < x < (q_j+q_k)/2 (s_lo < s_hi above), and both ends
  // are breakpoints (computed by the same expression), so a piece between consecutive breakpoints has a
  // fixed set of pairs. For N evenly spaced slits a piece holds O(N) of the N² pairs.
  const std::size_t n = intervals_.size(), pieces = breakpoints_.size() + 1;
  active_begin_.assign(1, 0);
  for (std::size_t i = 0; i < pieces; ++i) {
    const double lower = i == 0 ? -kInf : breakpoints_[i - 1];
    const double upper = i == pieces - 1 ? kInf : breakpoints_[i];
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t k = 0; k < n; ++k)
        if (0.5 * (intervals_[j].first + intervals_[k].first) <= lower &&
            0.5 * (intervals_[j].second + intervals_[k].second) >= upper)
          active_pairs_.push_back(static_cast<std::uint32_t>(j * n + k));
    active_begin_.push_back(active_pairs_.size());
  }
}

std::shared_ptr<Openings> Openings::slit(double width_m, double centre_m) {
  core::requirePositive("slit width", width_m);
  return std::make_shared<Openings>(
      std::vector<std::pair<double, double>>{{centre_m - 0.5 * width_m, centre_m + 0.5 * width_m}});
}

std::shared_ptr<Openings> Openings::slits(int count, double width_m, double spacing_m) {
  if (count < 1 || count > 64) throw core::InputError("slit count", "must be from 1 to 64");
  core::requirePositive("slit width", width_m);
  if (count > 1) core::requirePositive("slit spacing", spacing_m);
  if (count > 1 && spacing_m <= width_m)
    throw core::InputError("slit spacing", "must exceed the slit width (slits would overlap)");
  std::vector<std::pair<double, double>> v;
  for (int i = 0; i < count; ++i) {
    const double c = (i - 0.5 * (count - 1)) * spacing_m;
    v.emplace_back(c - 0.5 * width_m, c + 0.5 * width_m);
  }
  return std::make_shared<Openings>(std::move(v));
}

std::shared_ptr<Openings> Openings::halfPlane(double table_extent_m) {
  core::requirePositive("half-plane table extent", table_extent_m);
  auto o = std::make_shared<Openings>(std::vector<std::pair<double, double>>{{0.0, kInf}});
  o->half_plane_ = true;
  o->half_plane_extent_ = table_extent_m;
  return o;
}

std::complex<double> Openings::transmittance(double x_m) const {
  for (const auto& [p, q] : intervals_)
    if (x_m >= p && x_m <= q) return 1.0;
  return 0.0;
}

double Openings::wdf(double x, double u) const {
  const auto piece = std::upper_bound(breakpoints_.begin(), breakpoints_.end(), x) - breakpoints_.begin();
  return pieceWdf(static_cast<std::size_t>(piece), x, u);
}

double Openings::pieceWdf(std::size_t piece, double x, double u) const {
  double w = 0.0;
  for (std::size_t a = active_begin_[piece]; a < active_begin_[piece + 1]; ++a) {
    const auto [len, centre] = pairLag(active_pairs_[a], x);
    if (!(len > 0.0)) continue;  // x on the piece's boundary
    w += len * std::cos(2.0 * kPi * u * centre) * sinc(u * len);
  }
  return w;
}

double Openings::lagBound(double x) const {
  double b = 0.0;
  for (const auto& [p, q] : intervals_) {
    b = std::max(b, std::abs(x - p));
    if (std::isfinite(q)) b = std::max(b, std::abs(x - q));
  }
  return 2.0 * b;
}

int Openings::panelsFor(double mid, double width, double du) const {
  // Oscillation frequency in u is at most the lag bound (plus the sinc from the x-average).
  const double cycles = du * (lagBound(mid) + 2.0 * width);
  if (!(cycles < 1e4))
    throw core::InputError("WBSDF table", "a cell spans more than 10^4 oscillations of W; narrow the u range "
                                          "(--u-range) or the wavelength-to-size ratio");
  return 1 + static_cast<int>(cycles);
}

double Openings::cellMass(double x1, double x2, double u1, double u2) const {
  DIFFRAY_CHECK(x2 > x1 && u2 > u1);
  // Split [x1, x2] at breakpoints so that each piece is smooth (see the comment above); no allocation: this
  // runs once per table cell.
  double total = 0.0;
  forEachPiece(x1, x2, [&](double width, double mid, std::size_t piece) {
    const int panels = panelsFor(mid, width, u2 - u1);
    total += width * core::integrate([&](double u) { return pieceWdf(piece, mid, u) * sinc(2.0 * u * width); },
                                     u1, u2, panels, kCellNodes);
  });
  return total / (x2 - x1);
}

std::pair<double, double> Openings::support() const {
  if (half_plane_) return {0.0, half_plane_extent_};
  return {intervals_.front().first, intervals_.back().second};
}

double Openings::featureSize() const {
  double f = kInf;
  for (const auto& [p, q] : intervals_) f = std::min(f, q - p);
  for (std::size_t i = 1; i < intervals_.size(); ++i) {
    const double gap = intervals_[i].first - intervals_[i - 1].second;
    if (gap > 0.0) f = std::min(f, gap);  // touching openings have no gap to resolve
  }
  return half_plane_ ? half_plane_extent_ : f;
}

double Openings::coherenceLength() const {
  const auto [a, b] = support();
  return b - a;
}

// ---------------------------------------------------------------------------------------------------
// PhaseGrating (the paper's sinusoidal-grating example, Jacobi–Anger expansion).
// ---------------------------------------------------------------------------------------------------

PhaseGrating::PhaseGrating(double period_m, double modulation_m) : period_(period_m), modulation_(modulation_m) {
  core::requirePositive("grating period", period_m);
  core::requireFinite("grating modulation", modulation_m);
  if (std::abs(modulation_m) > 1000.0)
    throw core::InputError("grating modulation", "must lie within ±1000 (phase amplitude m/2 ≤ 500 rad)");
  const double half = 0.5 * std::abs(modulation_m);
  q_max_ = static_cast<int>(std::ceil(half + 6.0 * std::cbrt(half + 1.0) + 8.0));
  bessel_.resize(2 * q_max_ + 1);
  for (int q = -q_max_; q <= q_max_; ++q) {
    const double j = std::cyl_bessel_j(std::abs(q), std::abs(half));
    // J_{-q}(z) = (−1)^q J_q(z), J_q(−z) = (−1)^q J_q(z).
    const bool flip = ((q < 0) != (modulation_m < 0)) && (std::abs(q) % 2 == 1);
    bessel_[q + q_max_] = flip ? -j : j;
  }
}

std::complex<double> PhaseGrating::transmittance(double x_m) const {
  return std::polar(1.0, 0.5 * modulation_ * std::sin(2.0 * kPi * x_m / period_));
}

double PhaseGrating::lineWeight(int n, double x1, double x2) const {
  const double mid = 0.5 * (x1 + x2);
  const double width = x2 - x1;
  double w = 0.0;
  for (int q1 = -q_max_; q1 <= q_max_; ++q1) {
    const int q2 = n - q1;
    if (q2 < -q_max_ || q2 > q_max_) continue;
    const double kappa = (q1 - q2) / period_;  // cycles per metre of the cross term in x
    w += bessel_[q1 + q_max_] * bessel_[q2 + q_max_] * std::cos(2.0 * kPi * kappa * mid) * sinc(kappa * width);
  }
  return w;
}

double PhaseGrating::wdf(double x_m, double u_per_m) const {
  const int n = static_cast<int>(std::lround(u_per_m / lineSpacing()));
  return lineWeight(n, x_m, x_m);  // zero-width average: the pointwise line weight
}

double PhaseGrating::cellMass(double x1, double x2, double u1, double u2) const {
  double total = 0.0;
  const int n_lo = static_cast<int>(std::ceil(u1 / lineSpacing()));
  const int n_hi = static_cast<int>(std::floor(u2 / lineSpacing()));
  for (int n = n_lo; n <= n_hi; ++n)
    if (n * lineSpacing() >= u1 && n * lineSpacing() < u2) total += lineWeight(n, x1, x2);
  return total;
}

}  // namespace diffray::wbsdf
