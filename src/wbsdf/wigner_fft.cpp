#include "diffray/wbsdf/wigner_fft.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "diffray/core/error.h"
#include "diffray/core/fftw_planner.h"

namespace diffray::wbsdf {

namespace {

// Largest grids we agree to build (values, samples): beyond this a typo in dx or nu is far likelier than
// a real need, and the allocation would take the machine down.
constexpr double kMaxGridValues = 1u << 27;  // 1 GiB of doubles
constexpr double kMaxSamples = 1u << 26;

/// An in-place FFTW forward plan of length n on its own buffer. Planning and destruction hold
/// core::fftwPlannerMutex(); execute() on distinct objects may run concurrently (FFTW guarantees it).
class FftwForwardPlan {
 public:
  explicit FftwForwardPlan(int n) : n_(n) {
    buffer_ = static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * static_cast<size_t>(n)));
    DIFFRAY_CHECK(buffer_ != nullptr);
    std::lock_guard<std::mutex> lock(core::fftwPlannerMutex());
    // FFTW_ESTIMATE does not touch the buffer while planning.
    plan_ = fftw_plan_dft_1d(n, buffer_, buffer_, FFTW_FORWARD, FFTW_ESTIMATE);
    if (plan_ == nullptr) fftw_free(buffer_);
    DIFFRAY_CHECK(plan_ != nullptr);
  }
  ~FftwForwardPlan() {
    std::lock_guard<std::mutex> lock(core::fftwPlannerMutex());
    fftw_destroy_plan(plan_);
    fftw_free(buffer_);
  }
  FftwForwardPlan(const FftwForwardPlan&) = delete;
  FftwForwardPlan& operator=(const FftwForwardPlan&) = delete;

  /// The buffer as std::complex (layout-compatible with fftw_complex, C++ [complex.numbers]/4).
  std::complex<double>* data() { return reinterpret_cast<std::complex<double>*>(buffer_); }
  void clear() { std::fill(data(), data() + n_, std::complex<double>(0.0, 0.0)); }
  void execute() { fftw_execute(plan_); }

 private:
  int n_;
  fftw_complex* buffer_ = nullptr;
  fftw_plan plan_ = nullptr;
};

void validateProfile(const SampledProfile& profile, int nu, int kept) {
  const std::string where = "wignerFFT";
  if (profile.t.empty()) throw core::InputError(where, "the sampled profile is empty");
  core::requireFinite(where + ": profile x0_m", profile.x0_m);
  core::requirePositive(where + ": profile dx_m", profile.dx_m);
  if (nu < 2 || nu % 2 != 0) {
    throw core::InputError(where, "nu must be even and >= 2, got " + std::to_string(nu));
  }
  if (static_cast<double>(profile.t.size()) * kept > kMaxGridValues) {
    std::ostringstream s;
    s << profile.t.size() << " rows x " << kept << " columns exceeds the limit of " << kMaxGridValues
      << " values";
    throw core::InputError(where, s.str());
  }
  for (size_t i = 0; i < profile.t.size(); ++i) {
    if (!std::isfinite(profile.t[i].real()) || !std::isfinite(profile.t[i].imag())) {
      throw core::InputError(where, "profile sample " + std::to_string(i) + " is not finite");
    }
  }
}

}  // namespace

double WignerGrid::at(int j, int k) const {
  DIFFRAY_CHECK(j >= 0 && j < nx && k >= 0 && k < nu);
  return values[static_cast<size_t>(j) * static_cast<size_t>(nu) + static_cast<size_t>(k)];
}

void forwardFFT(std::vector<std::complex<double>>& data) {
  if (data.empty()) throw core::InputError("forwardFFT", "empty input");
  const int n = static_cast<int>(data.size());
  FftwForwardPlan plan(n);
  std::copy(data.begin(), data.end(), plan.data());
  plan.execute();
  std::copy(plan.data(), plan.data() + n, data.begin());
}

WignerGrid wignerFFT(const SampledProfile& profile, int nu, double u_keep_per_m) {
  if (!(u_keep_per_m >= 0.0)) throw core::InputError("wignerFFT", "u_keep_per_m must be >= 0");
  const int half = nu / 2;
  const double dx_m = profile.dx_m;
  // Lag x' = 2m·dx, so the FFT over m (length nu) has frequency step 1/(2·nu·dx) (eq:R_WDF).
  const double du_per_m = dx_m > 0 && nu >= 2 ? 1.0 / (2.0 * nu * dx_m) : 1.0;
  // Columns kept: k = −keep … keep−1 (all nu when u_keep is 0 or reaches the period's edge).
  const int keep = u_keep_per_m > 0.0 ? static_cast<int>(std::min<double>(half, std::ceil(u_keep_per_m / du_per_m)))
                                      : half;
  validateProfile(profile, nu, 2 * keep);
  const auto& t = profile.t;
  const int nx = static_cast<int>(t.size());

  WignerGrid grid;
  grid.x0_m = profile.x0_m;
  grid.dx_m = dx_m;
  grid.nx = nx;
  grid.nu = 2 * keep;
  grid.du_per_m = du_per_m;
  grid.u0_per_m = -keep * grid.du_per_m;
  grid.values.assign(static_cast<size_t>(nx) * static_cast<size_t>(grid.nu), 0.0);

  FftwForwardPlan plan(nu);  // one plan, reused for every row
  std::complex<double>* kernel = plan.data();
  for (int j = 0; j < nx; ++j) {
    // Mutual intensity J(x_j, 2m·dx) = t[j+m]·t*[j−m], zero outside the samples. It is Hermitian in m
    // (J(−m) = J(m)*), so its transform is real. Lag m goes to bin m mod nu.
    plan.clear();
    const int m_max = std::min({j, nx - 1 - j, half});
    for (int m = 0; m <= m_max; ++m) {
      const std::complex<double> j_m = t[j + m] * std::conj(t[j - m]);
      if (m == half) {
        // Lags +half and −half alias to the same bin: store their average, Re J, to stay Hermitian.
        kernel[half] = std::complex<double>(j_m.real(), 0.0);
      } else {
        kernel[m] = j_m;
        if (m > 0) kernel[nu - m] = std::conj(j_m);
      }
    }
    plan.execute();  // kernel[b] ← Σ_m J_m e^{−2πi·b·m/nu} = Σ_m J_m e^{−i4π·u_b·m·dx}
    double* row = grid.values.data() + static_cast<size_t>(j) * static_cast<size_t>(grid.nu);
    for (int c = 0; c < grid.nu; ++c) {
      // Column c holds u = (c − keep)·du, i.e. FFT bin (c − keep) mod nu.
      const std::complex<double> w = 2.0 * dx_m * kernel[(c - keep + nu) % nu];
      row[c] = w.real();
      grid.max_abs_imag = std::max(grid.max_abs_imag, std::abs(w.imag()));
    }
  }
  return grid;
}

SampledProfile sampleProfile(const std::function<std::complex<double>(double)>& t, double x0_m,
                             double x1_m, double dx_m) {
  const std::string where = "sampleProfile";
  core::requireFinite(where + ": x0_m", x0_m);
  core::requireFinite(where + ": x1_m", x1_m);
  core::requirePositive(where + ": dx_m", dx_m);
  if (!(x1_m > x0_m)) throw core::InputError(where, "x1_m must be greater than x0_m");
  if (!t) throw core::InputError(where, "no transmittance function given");
  const double count = std::floor((x1_m - x0_m) / dx_m + 1e-9) + 1.0;
  if (count > kMaxSamples) {
    std::ostringstream s;
    s << "(x1 - x0)/dx gives " << count << " samples, more than the limit of " << kMaxSamples;
    throw core::InputError(where, s.str());
  }
  SampledProfile profile;
  profile.x0_m = x0_m;
  profile.dx_m = dx_m;
  const int n = static_cast<int>(count);
  profile.t.resize(static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) {
    const double x_m = x0_m + j * dx_m;
    const std::complex<double> value = t(x_m);
    if (!std::isfinite(value.real()) || !std::isfinite(value.imag())) {
      std::ostringstream s;
      s << "t(x) is not finite at x = " << x_m << " m";
      throw core::InputError(where, s.str());
    }
    profile.t[static_cast<size_t>(j)] = value;
  }
  return profile;
}

}  // namespace diffray::wbsdf
