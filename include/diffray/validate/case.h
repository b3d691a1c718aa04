#pragma once
// Validation cases: each traces a scene through the real transport (Embree, WBSDF tables) and compares
// the receivers with an oracle from the reference module, which shares no code with the tracer.
// A case takes its physical parameters by name (a width, a wavelength, a distance...) so users can
// validate their own configuration. Cases are pure functions of (parameters, rays, seed): thread-safe.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace diffray::validate {

using Params = std::map<std::string, std::vector<double>>;

struct ParamSpec {
  std::string name;                ///< option name without dashes, e.g. "width"
  std::vector<double> defaults;    ///< default value(s); several for sweeps (door-rs frequencies)
  std::string help;
  double min = 0.0;                ///< values must be > min (or >= min when min_inclusive) ...
  bool min_inclusive = false;
  /// ... and < max; checked by resolveParams before any case runs. The default bounds every length (and
  /// any other value) by the scenes' float range (room::kMaxCoordinateM, 1e6 m): beyond it Embree would see
  /// infinite coordinates.
  double max = 1e6;
  bool whole = false;  ///< a count or a switch (the case reads an int): 2.5 is refused, not read as 2
  bool list = false;   ///< several values allowed (a sweep, a point, per-band values); else exactly one
};

/// One receiver bin (or one grating order) of a case: screen position, traced and reference values.
struct Row {
  double x_m = 0, y_m = 0;
  double traced = 0, reference = 0, std_error = 0;
  double alt_reference = 0;  ///< a second oracle where a case has one (door-rs: the propagating field)
  std::string label;  ///< e.g. "f=500Hz" or "order=1"
};

struct CaseResult {
  std::string name;
  std::uint64_t rays = 0;
  double seconds = 0;
  double max_abs_error_rel_peak = 0;
  double rms_error_rel_peak = 0;
  double max_std_error_rel_peak = 0;   ///< largest bin standard error (estimator noise) over the peak
  double negative_energy_fraction = 0; ///< Σ negative bin energies / Σ |bin energies|
  double target_rel_peak = 0.01;
  bool passed = false;
  std::vector<Row> rows;
  std::map<std::string, double> extra;  ///< case-specific figures (energy balance, per-frequency errors)
  std::string detail;  ///< one line on what was compared, for cases whose errors are not "% of a peak"
  /// The error figures are level differences in dB (diffraction cases), not fractions of a peak.
  bool errors_in_db = false;
};

struct RunOptions {
  std::uint64_t rays = 0;  ///< 0: the case's default
  std::uint64_t seed = 1;
  bool qmc = true;  ///< randomised quasi-Monte Carlo (see core::ChunkSampler); false = plain Monte Carlo
  /// "wigner": the paper's WBSDF (default); "angle-impact": the angle-impact WBSDF (wbsdf/angle_impact.h),
  /// exact straight-ray transport of the propagating field in 2D (2D aperture cases only).
  std::string model = "wigner";
  std::function<void(std::uint64_t)> on_progress;
};

struct CaseInfo {
  std::string name;
  std::string summary;
  std::vector<ParamSpec> params;
  std::uint64_t default_rays;
  std::function<CaseResult(const Params&, const RunOptions&)> run;
  bool angle_impact = false;  ///< whether RunOptions::model = "angle-impact" applies
  /// The parameter `name` (InternalError when the case has none), to set its whole/list flags.
  ParamSpec& param(const std::string& param_name);
  const ParamSpec& param(const std::string& param_name) const;
};

/// Every case, in the order `validate all` runs them.
const std::vector<CaseInfo>& cases();
const CaseInfo* findCase(const std::string& name);
/// Fills defaults for unset parameters; throws InputError for a parameter the case does not take.
Params resolveParams(const CaseInfo& info, const Params& given);

/// Fills the error figures of `r` from its rows (peak = largest |reference|).
void scoreRows(CaseResult& r);

}  // namespace diffray::validate
