#pragma once
// One-dimensional occluder microstructures t(x) = a(x)·e^{iΦ(x)} (paper eq. eq:microstructure) along an
// occluder's local x axis, in metres, with their Wigner distributions W(x,u) in closed form (paper eq. 2,
// eq:R_WDF; u in cycles per metre). A Microstructure knows how to integrate its own W over a table cell,
// which is what WbsdfTable stores. Immutable after construction; all methods are thread-safe.
#include <algorithm>
#include <complex>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace diffray::wbsdf {

class Microstructure {
 public:
  virtual ~Microstructure() = default;

  virtual std::complex<double> transmittance(double x_m) const = 0;
  /// Closed-form Wigner distribution W(x,u) (paper eq. 2). For line spectra (gratings), the weight of the
  /// line nearest to u instead (see lineSpacing()).
  virtual double wdf(double x_m, double u_per_m) const = 0;
  /// (1/(x2−x1)) ∫_{x1}^{x2} ∫_{u1}^{u2} W(x,u) du dx: the cell value a WbsdfTable stores.
  virtual double cellMass(double x1_m, double x2_m, double u1_per_m, double u2_per_m) const = 0;
  /// cellMass of `count` consecutive cells [x1, x2] × [u_first + k·du, u_first + (k+1)·du], k = 0 … count−1,
  /// into out[k]: a table row. The default calls cellMass per cell; a structure may share work along the row.
  virtual void rowMasses(double x1_m, double x2_m, double u_first_per_m, double du_per_m, int count,
                         double* out) const;

  /// Where t can be non-zero (or one period, for periodic structures).
  virtual std::pair<double, double> support() const = 0;
  virtual bool periodic() const { return false; }
  /// True when t ≡ 1 beyond support() on the right (a half-plane's open side): rays pass straight.
  virtual bool openBeyondSupport() const { return false; }
  /// Smallest length that shapes W (a slit width, a grating period): sets the table's x resolution.
  virtual double featureSize() const = 0;
  /// Largest coherent length (the whole structure's span): sets the table's u resolution.
  virtual double coherenceLength() const = 0;
  /// > 0 for structures whose W is a sum of δ lines in u at multiples of this spacing (gratings).
  virtual double lineSpacing() const { return 0.0; }
};

/// Openings [begin, end] in an opaque screen: a slit, N slits, a door, or a half-plane edge (end = +inf).
/// W is the sum of the cross-Wigner distributions of every pair of openings (for two slits,
/// W_r(x−d/2) + W_r(x+d/2) + 2cos(2πud)·W_r(x), the signed cross term lying midway between them).
class Openings : public Microstructure {
 public:
  explicit Openings(std::vector<std::pair<double, double>> intervals_m);
  static std::shared_ptr<Openings> slit(double width_m, double centre_m = 0.0);
  static std::shared_ptr<Openings> slits(int count, double width_m, double spacing_m);
  /// The half-plane x ≥ 0 is open; `table_extent_m` is how far past the edge the table reaches (beyond
  /// it the structure is treated as fully open: W → δ(u)).
  static std::shared_ptr<Openings> halfPlane(double table_extent_m);

  std::complex<double> transmittance(double x_m) const override;
  double wdf(double x_m, double u_per_m) const override;
  double cellMass(double x1_m, double x2_m, double u1_per_m, double u2_per_m) const override;
  /// cellMass's quadrature cell by cell, with the cosines and sines of the whole row from one rotation per
  /// panel (openings_row.cpp). The panel count comes from du; cellMass takes u2 − u1, which can round to
  /// one panel more or fewer when the count sits on an integer (a quadrature difference of ~1e-7 of the
  /// cell's bound at worst, far below what the table needs).
  void rowMasses(double x1_m, double x2_m, double u_first_per_m, double du_per_m, int count,
                 double* out) const override;
  std::pair<double, double> support() const override;
  bool openBeyondSupport() const override { return half_plane_; }
  double featureSize() const override;
  double coherenceLength() const override;
  const std::vector<std::pair<double, double>>& intervals() const { return intervals_; }

 private:
  /// Bound on |s| (the lag) at x: sets the u quadrature density.
  double lagBound(double x_m) const;
  /// Gauss–Legendre panels cellMass uses on a piece of width `width_m` at `mid_m` for cells du wide;
  /// throws InputError past 10^4 oscillations per cell.
  int panelsFor(double mid_m, double width_m, double du_per_m) const;
  static constexpr int kCellNodes = 6;  ///< Gauss–Legendre nodes per panel of a cell's u quadrature
  /// Calls f(width, mid, piece) for each piece of [x1, x2] between breakpoints (W is smooth on each; see
  /// microstructure.cpp), in order of x, with `piece` its index for pieceWdf and active_pairs_.
  template <class F>
  void forEachPiece(double x1_m, double x2_m, F&& f) const {
    auto next = std::upper_bound(breakpoints_.begin(), breakpoints_.end(), x1_m);
    for (double lo = x1_m; lo < x2_m;) {
      double hi = x2_m;
      if (next != breakpoints_.end() && *next < x2_m) hi = *next++;
      const double mid = 0.5 * (lo + hi);
      const auto piece = static_cast<std::size_t>(
          std::upper_bound(breakpoints_.begin(), breakpoints_.end(), mid) - breakpoints_.begin());
      f(hi - lo, mid, piece);
      lo = hi;
    }
  }
  /// The lag interval s ∈ [s_lo, s_hi] of active pair `pair` (j·n + k) at x, as its length (≤ 0: the pair's
  /// term vanishes there) and centre; the pair's term is len·cos(2πu·centre)·sinc(u·len).
  struct Lag {
    double len, centre;
  };
  Lag pairLag(std::uint32_t pair, double x) const {
    const std::size_t n = intervals_.size();
    const auto& [pj, qj] = intervals_[pair / n];
    const auto& [pk, qk] = intervals_[pair % n];
    const double s_lo = std::max(2.0 * (pj - x), 2.0 * (x - qk));
    const double s_hi = std::min(2.0 * (qj - x), 2.0 * (x - pk));
    return {s_hi - s_lo, 0.5 * (s_lo + s_hi)};
  }
  /// W at x from the pairs active in `piece` (see active_pairs_); x must lie in that piece.
  double pieceWdf(std::size_t piece, double x_m, double u_per_m) const;
  std::vector<std::pair<double, double>> intervals_;
  std::vector<double> breakpoints_;  ///< x where some pair's lag limits change slope (sorted)
  /// Pairs (j·n + k) whose cross term is non-zero somewhere in each piece between breakpoints: piece i
  /// (0 … breakpoints_.size()) lies below breakpoints_[i] (and above breakpoints_[i−1]); its pairs are
  /// active_pairs_[active_begin_[i] … active_begin_[i+1]), in (j,k) order so sums stay bit-identical.
  std::vector<std::uint32_t> active_pairs_;
  std::vector<std::size_t> active_begin_;
  bool half_plane_ = false;
  double half_plane_extent_ = 0.0;
};

/// Sinusoidal phase grating t = exp(i(m/2)·sin(2πx/Λ)) (paper eq. for the sinusoidal grating):
/// W = Σ_{q1,q2} J_q1 J_q2 cos(2πx(q1−q2)/Λ) δ(u − (q1+q2)/(2Λ)); orders carry J_q(m/2)² on average.
class PhaseGrating : public Microstructure {
 public:
  PhaseGrating(double period_m, double modulation_m);
  std::complex<double> transmittance(double x_m) const override;
  double wdf(double x_m, double u_per_m) const override;
  double cellMass(double x1_m, double x2_m, double u1_per_m, double u2_per_m) const override;
  std::pair<double, double> support() const override { return {0.0, period_}; }
  bool periodic() const override { return true; }
  double featureSize() const override { return period_; }
  double coherenceLength() const override { return period_; }
  double lineSpacing() const override { return 0.5 / period_; }
  double period() const { return period_; }

 private:
  /// Weight of line n, x-averaged over [x1, x2].
  double lineWeight(int n, double x1_m, double x2_m) const;
  double period_;
  double modulation_;
  int q_max_;
  std::vector<double> bessel_;  ///< J_q(m/2) for q = −q_max … q_max
};

}  // namespace diffray::wbsdf
