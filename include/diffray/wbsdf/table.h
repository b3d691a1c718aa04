#pragma once
// A tabulated one-dimensional WBSDF with importance sampling (Cuypers et al. 2012, section
// "Implementation": "the pdf is calculated using the absolute values ... in the lookup table").
//
// Rows are x-cells of width dx on the occluder's local x axis (metres); columns are u-cells of width du
// (cycles per metre) of the *shift* u' = u_o − u_i (angle-shift invariance, paper eq. 8 eq:transmission).
// Cell (j,k) stores the x-averaged, u-integrated signed mass of W. Sampling at position x picks the row
// containing x and inverts the row's cumulative |mass| with one uniform: a monotone map, so stratified or
// quasi-random uniforms stay stratified in u'. Within a cell u' is uniform (continuous tables) or the cell
// centre (line spectra, e.g. gratings). The ray's energy is
// multiplied by weight = sign(mass)·Σ|mass|, so E[weight] = Σ mass = x-average of |t|²: energy is
// conserved on average and the sign travels in the ray. Immutable after construction; thread-safe.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "diffray/wbsdf/microstructure.h"
#include "diffray/wbsdf/wigner_fft.h"

namespace diffray::wbsdf {

struct TableLayout {
  double x0_m = 0.0, dx_m = 1.0;       ///< row j covers [x0 + j dx, x0 + (j+1) dx)
  int nx = 1;
  double u0_per_m = 0.0, du_per_m = 1.0;  ///< column k covers [u0 + k du, u0 + (k+1) du)
  int nu = 1;
  bool periodic = false;        ///< x wraps modulo nx·dx
  bool open_beyond = false;     ///< x past the last row: t = 1, rays pass straight (half-plane)
  bool line_spectrum = false;   ///< sample cell centres instead of uniform positions in the cell
};

/// Options that choose a table's resolution from the wavelength and the microstructure's feature size.
struct TableOptions {
  double wavelength_m = 0.0;
  /// Half-range of tabulated shifts u'. 0 → 2/λ (every shift that can leave a propagating ray for any
  /// incidence); larger values are clamped to 2/λ. A smaller range (for near-normal incidence and small screens) saves memory; the mass
  /// outside it is reported by truncatedMass().
  double u_half_range_per_m = 0.0;
  int cells_per_coherence = 32;  ///< du = 1/(this · coherence length)
  int rows_per_feature = 64;     ///< dx = feature size / this
  std::size_t max_cells = 40'000'000;
  /// When the table would exceed max_cells: widen du to fit (true) or throw InputError (false).
  bool coarsen_to_fit = false;
  /// Progress: called after each finished row with the table's row count, from worker threads (so it
  /// must be thread-safe; core::progressOfUnknownSize makes one that draws a bar). Empty: none.
  std::function<void(std::uint64_t rows)> on_row;
};

class WbsdfTable {
 public:
  WbsdfTable(TableLayout layout, std::vector<double> masses, double truncated_mass = 0.0);

  /// Builds the table of a microstructure from its closed-form cell integrals (in parallel).
  static std::shared_ptr<const WbsdfTable> build(const Microstructure& m, const TableOptions& options);
  /// A table from a numeric Wigner distribution (wigner_fft.h): rows are the grid's rows (cells
  /// [x_j − dx/2, x_j + dx/2)), columns its columns (cells [u_k − du/2, u_k + du/2)), masses W·du.
  static std::shared_ptr<const WbsdfTable> fromWigner(const WignerGrid& grid);

  struct Sample {
    double u_shift = 0.0;  ///< sampled u' (cycles per metre)
    double weight = 0.0;   ///< sign(mass)·Σ|mass| of the row; 0 when the ray is absorbed (t = 0 there)
  };
  /// Samples u' at position x from one uniform in [0,1) (inverse of the row's |W| distribution).
  Sample sample(double x_m, double xi) const;
  /// The unimportance-sampled alternative (the render-is bench): u' uniform over the tabulated range
  /// [u0, u0 + nu·du) (line spectra: a cell uniformly), weight W(x, u')/p_uniform = mass·nu, so
  /// E[weight·f(u')] = Σ mass·f, the same expectation as sample(); zero-mass cells give weight 0.
  Sample sampleUniform(double x_m, double xi) const;
  /// Probability density of u' at x (per unit u; for line spectra, the probability of the cell).
  double pdf(double x_m, double u_shift) const;
  /// The tabulated W at (x, u'): mass/du (for line spectra, the mass of the cell).
  double eval(double x_m, double u_shift) const;

  const TableLayout& layout() const { return layout_; }
  double mass(int row, int col) const { return masses_[static_cast<std::size_t>(row) * layout_.nu + col]; }
  double rowAbsMass(int row) const { return row_abs_[row]; }
  /// Signed mass of shifts outside the tabulated range, x-averaged over the whole table.
  double truncatedMass() const { return truncated_mass_; }
  /// Fraction of Σ|mass| that is negative: how signed this WBSDF is.
  double negativeFraction() const;
  std::size_t bytes() const;

 private:
  /// Row of x, or −1 outside a non-periodic table (−2 when open beyond it).
  int rowOf(double x_m) const;
  TableLayout layout_;
  double inv_dx_ = 1.0;
  std::vector<double> masses_;
  std::vector<double> row_abs_;
  std::vector<double> cdf_;  ///< per row: nu + 1 running sums of |mass|, starting at 0
  /// per row: nu entries, guide_[i] = the cell holding the quantile i/nu (Chen–Asau guide table), so the
  /// inversion is a lookup and a short forward scan instead of a binary search.
  std::vector<std::uint32_t> guide_;
  double truncated_mass_;
};

}  // namespace diffray::wbsdf
