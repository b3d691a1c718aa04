#include "diffray/wbsdf/angle_impact.h"

#include <tbb/parallel_for.h>

#include <cmath>

#include "diffray/core/error.h"
#include "diffray/core/math.h"
#include "diffray/wbsdf/wigner_fft.h"

namespace diffray::wbsdf {

using core::kPi;
using Cx = std::complex<double>;

std::complex<double> openingsSpectrum(const Openings& openings, double u) {
  Cx sum = 0.0;
  for (const auto& [p, q] : openings.intervals()) {
    if (!std::isfinite(q)) throw core::InputError("openings", "the angle-impact model needs finite openings");
    // ∫_p^q e^{−i2πux} dx = (q − p)·sinc(u(q − p))·e^{−iπu(p + q)}, stable at u = 0.
    sum += (q - p) * core::sinc(u * (q - p)) * std::polar(1.0, -kPi * u * (p + q));
  }
  return sum;
}

namespace {

// W_AI(θ, b) on a grid of b for one direction θ: the integral over Δ becomes a Fourier transform in
// v = (2/λ)·sin(Δ/2) (dΔ = λ dv / cos(Δ/2)), evaluated by one FFT. Returns values at b_m = (m − n/2)·db.
struct ImpactRow {
  std::vector<double> w;
  double db = 0.0;
  int n = 0;
  double at(double b) const {
    const double r = b / db + 0.5 * n;
    const int m = static_cast<int>(std::floor(r));
    if (m < 0 || m + 1 >= n) return 0.0;
    const double f = r - m;
    return (1.0 - f) * w[m] + f * w[m + 1];
  }
};

ImpactRow impactRow(const std::function<Cx(double)>& spectrum, double theta, double lambda, double b_range,
                    int pad) {
  const double v_max = 2.0 * std::cos(theta) / lambda;
  const double dv = 1.0 / b_range;
  int nv = 2;
  while (nv * dv < 2.0 * v_max) nv *= 2;
  const int n = nv * pad;  // zero padding: a finer b grid to interpolate on
  std::vector<Cx> g(n, 0.0);
  for (int j = 0; j < n; ++j) {
    const double v = (j - n / 2) * dv;
    if (std::abs(v) >= v_max) continue;
    const double half = std::asin(0.5 * lambda * v);  // Δ/2
    const double t1 = theta + half, t2 = theta - half;
    const double jac = lambda / std::cos(half);
    g[j] = jac * (std::cos(t1) * std::cos(t2) / (lambda * lambda)) * spectrum(std::sin(t1) / lambda) *
           std::conj(spectrum(std::sin(t2) / lambda)) * dv;
  }
  // W(b_m) = Σ_j g_j e^{+i2π v_j b_m}, v_j = (j − n/2)dv, b_m = (m − n/2)db, db = 1/(n dv): an inverse DFT
  // with centred indices, done as conj(forwardFFT(conj(·))) with the (−1)^(j+m) shifts.
  for (int j = 0; j < n; ++j) g[j] = std::conj(g[j]) * ((j % 2) ? -1.0 : 1.0);
  forwardFFT(g);
  ImpactRow row;
  row.n = n;
  row.db = 1.0 / (n * dv);
  row.w.resize(n);
  const double phase_sign = ((n / 2) % 2) ? -1.0 : 1.0;  // e^{iπ n/2 ...} from centring both indices
  for (int m = 0; m < n; ++m) row.w[m] = phase_sign * std::real(std::conj(g[m])) * ((m % 2) ? -1.0 : 1.0);
  return row;
}

}  // namespace

std::shared_ptr<const WbsdfTable> angleImpactTable(const std::function<Cx(double)>& spectrum,
                                                   const AngleImpactOptions& o) {
  const double lambda = o.wavelength_m;
  core::requirePositive("wavelength", lambda);
  if (!(o.x_hi_m > o.x_lo_m)) throw core::InputError("aperture", "needs x_hi > x_lo");
  if (o.nu < 2 || o.nx < 1) throw core::InputError("angle-impact table", "needs nu >= 2 and nx >= 1");
  core::checkedCount("angle-impact table cells", static_cast<double>(o.nu) * o.nx, static_cast<double>(o.max_cells));
  const double margin = o.margin_m > 0 ? o.margin_m : 4.0 * lambda;
  TableLayout L;
  L.x0_m = o.x_lo_m - margin;
  L.nx = o.nx;
  L.dx_m = (o.x_hi_m - o.x_lo_m + 2.0 * margin) / o.nx;
  L.nu = o.nu;
  const double u_half = o.u_half_range_per_m > 0 ? std::min(o.u_half_range_per_m, 1.0 / lambda) : 1.0 / lambda;
  L.du_per_m = 2.0 * u_half / o.nu;
  L.u0_per_m = -u_half;
  const double extent = std::max(std::abs(L.x0_m), std::abs(L.x0_m + L.nx * L.dx_m));
  const double b_range = 4.0 * extent;  // the FFT's b period: twice the table's b span, no wrap-around
  std::vector<double> masses(static_cast<std::size_t>(L.nx) * L.nu, 0.0);
  const int sub_u = 4, sub_x = 4;  // cell averages from sub-samples
  tbb::parallel_for(0, L.nu, [&](int k) {
    std::vector<double> col(L.nx, 0.0);
    for (int su = 0; su < sub_u; ++su) {
      const double u = L.u0_per_m + (k + (su + 0.5) / sub_u) * L.du_per_m;
      const double theta = std::asin(std::clamp(lambda * u, -1.0, 1.0));
      const ImpactRow row = impactRow(spectrum, theta, lambda, b_range, 4);
      for (int j = 0; j < L.nx; ++j)
        for (int sx = 0; sx < sub_x; ++sx) {
          const double x0 = L.x0_m + (j + (sx + 0.5) / sub_x) * L.dx_m;
          col[j] += lambda * row.at(x0 * std::cos(theta)) / (sub_u * sub_x);
        }
    }
    for (int j = 0; j < L.nx; ++j) masses[static_cast<std::size_t>(j) * L.nu + k] = col[j] * L.du_per_m;
  });
  return std::make_shared<WbsdfTable>(L, std::move(masses));
}

}  // namespace diffray::wbsdf
