#include "diffray/wbsdf/table.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "diffray/core/error.h"

namespace diffray::wbsdf {

namespace {
/// Upper bound on the u-quadrature panels of one table build (a few minutes of work on one core).
constexpr double kMaxQuadraturePanels = 2e9;
}  // namespace

WbsdfTable::WbsdfTable(TableLayout layout, std::vector<double> masses, double truncated_mass)
    : layout_(layout), masses_(std::move(masses)), truncated_mass_(truncated_mass) {
  DIFFRAY_CHECK(layout_.nx >= 1 && layout_.nu >= 1 && layout_.dx_m > 0 && layout_.du_per_m > 0);
  DIFFRAY_CHECK(masses_.size() == static_cast<std::size_t>(layout_.nx) * layout_.nu);
  inv_dx_ = 1.0 / layout_.dx_m;
  row_abs_.resize(layout_.nx);
  cdf_.resize(static_cast<std::size_t>(layout_.nx) * (layout_.nu + 1));
  guide_.resize(masses_.size());
  tbb::parallel_for(0, layout_.nx, [&](int j) {
    const double* m = &masses_[static_cast<std::size_t>(j) * layout_.nu];
    double* c = &cdf_[static_cast<std::size_t>(j) * (layout_.nu + 1)];
    c[0] = 0.0;
    for (int k = 0; k < layout_.nu; ++k) c[k + 1] = c[k] + std::abs(m[k]);
    row_abs_[j] = c[layout_.nu];
    std::uint32_t* g = &guide_[static_cast<std::size_t>(j) * layout_.nu];
    int k = 0;
    for (int i = 0; i < layout_.nu; ++i) {
      const double q = row_abs_[j] * i / layout_.nu;
      while (k < layout_.nu - 1 && c[k + 1] <= q) ++k;
      g[i] = static_cast<std::uint32_t>(k);
    }
  });
}

std::shared_ptr<const WbsdfTable> WbsdfTable::build(const Microstructure& m, const TableOptions& o) {
  core::requirePositive("wavelength", o.wavelength_m);
  TableLayout L;
  const auto [x_lo, x_hi] = m.support();
  L.periodic = m.periodic();
  L.open_beyond = m.openBeyondSupport();
  L.x0_m = x_lo;
  const double feature = std::min(m.featureSize(), x_hi - x_lo);
  // Rows: fine enough for the feature, and for the half-plane (whose W varies on the scale of λ) at
  // least 8 per wavelength.
  double dx = feature / o.rows_per_feature;
  if (L.open_beyond) dx = std::min(dx, o.wavelength_m / 8.0);
  const double max_cells = static_cast<double>(o.max_cells);
  L.nx = core::checkedCount("WBSDF table rows", (x_hi - x_lo) / dx, max_cells);
  L.dx_m = (x_hi - x_lo) / L.nx;

  // Shifts beyond 2/λ are evanescent for every incidence (|u_i|, |u_o| ≤ 1/λ), so a wider range is clamped.
  const double full_range = 2.0 / o.wavelength_m;
  const double half_range = o.u_half_range_per_m > 0 ? std::min(o.u_half_range_per_m, full_range) : full_range;
  if (m.lineSpacing() > 0) {
    L.line_spectrum = true;
    L.du_per_m = m.lineSpacing();
    const int n_half = core::checkedCount("WBSDF table lines", std::floor(half_range / L.du_per_m), max_cells);
    L.nu = 2 * n_half + 1;
    L.u0_per_m = -(n_half + 0.5) * L.du_per_m;  // cells centred on the lines
  } else {
    const double wanted = 2.0 * half_range * o.cells_per_coherence * m.coherenceLength();
    L.nu = std::max(2, core::checkedCount("WBSDF table columns",
                                          o.coarsen_to_fit ? std::min(wanted, max_cells) : wanted, max_cells));
    L.nu += L.nu % 2;  // symmetric about u' = 0
    if (o.coarsen_to_fit && static_cast<std::size_t>(L.nx) * L.nu > o.max_cells) {
      L.nu = std::max(2, static_cast<int>(o.max_cells / static_cast<std::size_t>(L.nx)));
      L.nu -= L.nu % 2;  // stay even, rounding down so the limit holds
    }
    L.du_per_m = 2.0 * half_range / L.nu;
    L.u0_per_m = -half_range;
  }
  const std::size_t cells = static_cast<std::size_t>(L.nx) * L.nu;
  if (cells > o.max_cells)
    throw core::InputError("WBSDF table", std::to_string(L.nx) + " x " + std::to_string(L.nu) +
                                              " cells exceed the limit of " + std::to_string(o.max_cells) +
                                              "; narrow the u range or coarsen the resolution");
  // Quadrature work: every cell takes ≥ 1 panel plus one per oscillation of W across it (cellMass), and the
  // lag, which sets the oscillation rate, is bounded by about twice the coherence length.
  const double panels = static_cast<double>(cells) + L.nx * 4.0 * half_range * m.coherenceLength();
  if (!(panels <= kMaxQuadraturePanels))
    throw core::InputError("WBSDF table", "needs about " + std::to_string(panels) +
                                              " quadrature panels, more than the limit of " +
                                              std::to_string(kMaxQuadraturePanels) + "; narrow the u range");
  std::vector<double> masses(cells);
  std::vector<double> row_total(L.nx);
  tbb::parallel_for(0, L.nx, [&](int j) {
    const double x1 = L.x0_m + j * L.dx_m, x2 = x1 + L.dx_m;
    double* row = &masses[static_cast<std::size_t>(j) * L.nu];
    m.rowMasses(x1, x2, L.u0_per_m, L.du_per_m, L.nu, row);
    double sum = 0.0;
    for (int k = 0; k < L.nu; ++k) sum += row[k];
    // Σ_u W = |t|² (the Wigner distribution's u-marginal): what the row misses lies outside the u range.
    double t2 = 0.0;
    const int probes = 16;
    for (int p = 0; p < probes; ++p) t2 += std::norm(m.transmittance(x1 + (p + 0.5) * L.dx_m / probes));
    row_total[j] = t2 / probes - sum;
    if (o.on_row) o.on_row(static_cast<std::uint64_t>(L.nx));
  });
  double truncated = 0.0;
  for (double r : row_total) truncated += r;
  return std::make_shared<WbsdfTable>(L, std::move(masses), truncated / L.nx);
}

std::shared_ptr<const WbsdfTable> WbsdfTable::fromWigner(const WignerGrid& g) {
  TableLayout L;
  L.x0_m = g.x0_m - 0.5 * g.dx_m;
  L.dx_m = g.dx_m;
  L.nx = g.nx;
  L.u0_per_m = g.u0_per_m - 0.5 * g.du_per_m;
  L.du_per_m = g.du_per_m;
  L.nu = g.nu;
  std::vector<double> masses(g.values.size());
  for (std::size_t i = 0; i < masses.size(); ++i) masses[i] = g.values[i] * g.du_per_m;
  return std::make_shared<WbsdfTable>(L, std::move(masses));
}

int WbsdfTable::rowOf(double x) const {
  double r = (x - layout_.x0_m) * inv_dx_;
  if (layout_.periodic) {
    r = std::fmod(r, static_cast<double>(layout_.nx));
    if (r < 0) r += layout_.nx;
  } else if (r < 0.0 || r >= layout_.nx) {
    return (layout_.open_beyond && r >= layout_.nx) ? -2 : -1;
  }
  return std::min(static_cast<int>(r), layout_.nx - 1);
}

WbsdfTable::Sample WbsdfTable::sample(double x, double xi) const {
  const int row = rowOf(x);
  if (row == -2) return {0.0, 1.0};  // fully open: straight through with unit weight
  if (row < 0 || row_abs_[row] <= 0.0) return {0.0, 0.0};
  const double* c = &cdf_[static_cast<std::size_t>(row) * (layout_.nu + 1)];
  const double target = xi * row_abs_[row];
  // First k with c[k+1] > target (cells of zero mass are never chosen). It lies between the guide
  // entries of this quantile bucket and the next, usually 0–2 cells apart: bisect that short range.
  const int nu = layout_.nu;
  const int bucket = std::min(static_cast<int>(xi * nu), nu - 1);
  const std::uint32_t* g = &guide_[static_cast<std::size_t>(row) * nu];
  int k = static_cast<int>(g[bucket]);
  int hi = bucket + 1 < nu ? static_cast<int>(g[bucket + 1]) : nu - 1;
  while (k < hi) {
    const int mid = (k + hi) >> 1;
    const bool right = c[mid + 1] <= target;
    k = right ? mid + 1 : k;
    hi = right ? hi : mid;
  }
  const double m = masses_[static_cast<std::size_t>(row) * layout_.nu + k];
  Sample s;
  s.weight = m >= 0 ? row_abs_[row] : -row_abs_[row];
  const double within = layout_.line_spectrum ? 0.5 : std::clamp((target - c[k]) / std::abs(m), 0.0, 1.0);
  s.u_shift = layout_.u0_per_m + (k + within) * layout_.du_per_m;
  return s;
}

WbsdfTable::Sample WbsdfTable::sampleUniform(double x, double xi) const {
  const int row = rowOf(x);
  if (row == -2) return {0.0, 1.0};
  if (row < 0 || row_abs_[row] <= 0.0) return {0.0, 0.0};
  const double pos = std::clamp(xi, 0.0, 1.0) * layout_.nu;
  const int k = std::min(static_cast<int>(pos), layout_.nu - 1);
  Sample s;
  s.weight = mass(row, k) * layout_.nu;
  s.u_shift = layout_.u0_per_m + (layout_.line_spectrum ? k + 0.5 : pos) * layout_.du_per_m;
  return s;
}

double WbsdfTable::pdf(double x, double u) const {
  const int row = rowOf(x);
  if (row < 0 || row_abs_[row] <= 0.0) return 0.0;
  const int k = static_cast<int>(std::floor((u - layout_.u0_per_m) / layout_.du_per_m));
  if (k < 0 || k >= layout_.nu) return 0.0;
  const double p = std::abs(mass(row, k)) / row_abs_[row];
  return layout_.line_spectrum ? p : p / layout_.du_per_m;
}

double WbsdfTable::eval(double x, double u) const {
  const int row = rowOf(x);
  if (row < 0) return 0.0;
  const int k = static_cast<int>(std::floor((u - layout_.u0_per_m) / layout_.du_per_m));
  if (k < 0 || k >= layout_.nu) return 0.0;
  return layout_.line_spectrum ? mass(row, k) : mass(row, k) / layout_.du_per_m;
}

double WbsdfTable::negativeFraction() const {
  double neg = 0.0, all = 0.0;
  for (double m : masses_) {
    all += std::abs(m);
    if (m < 0) neg -= m;
  }
  return all > 0 ? neg / all : 0.0;
}

std::size_t WbsdfTable::bytes() const {
  return (masses_.size() + cdf_.size() + row_abs_.size()) * sizeof(double) + guide_.size() * sizeof(std::uint32_t);
}

}  // namespace diffray::wbsdf
