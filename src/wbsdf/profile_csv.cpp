#include "diffray/wbsdf/profile_csv.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "diffray/core/error.h"
#include "diffray/core/number.h"

namespace diffray::wbsdf {

namespace {

constexpr double kMaxResampledPoints = 1u << 26;
const char* const kColumnNames[3] = {"x", "amplitude", "phase"};

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  const auto end = s.find_last_not_of(" \t\r\n");
  return s.substr(begin, end - begin + 1);
}

std::vector<std::string> splitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream stream(line);
  while (std::getline(stream, field, ',')) fields.push_back(trim(field));
  if (!line.empty() && line.back() == ',') fields.emplace_back();  // trailing empty column
  return fields;
}

/// Whether a first line is a header (column names): none of its fields reads as a number in any syntax
/// strtod knows, so that "0x1p-3,1,0" is a data line (refused: numbers are decimal) rather than skipped.
bool isHeader(const std::vector<std::string>& fields) {
  for (const std::string& f : fields) {
    char* end = nullptr;
    std::strtod(f.c_str(), &end);
    if (!f.empty() && end == f.c_str() + f.size()) return false;
  }
  return true;
}

}  // namespace

ProfilePoints readProfileCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw core::InputError(path, "cannot open the profile file");

  ProfilePoints points;
  std::string raw;
  int line_no = 0;
  bool seen_first_content_line = false;
  while (std::getline(in, raw)) {
    ++line_no;
    const std::string line = trim(raw.substr(0, raw.find('#')));
    if (line.empty()) continue;
    const std::string where = path + ":" + std::to_string(line_no);
    const std::vector<std::string> fields = splitFields(line);

    if (!seen_first_content_line) {
      seen_first_content_line = true;
      if (isHeader(fields)) continue;
    }
    if (fields.size() != 3) {
      throw core::InputError(where, "expected 3 columns (x, amplitude, phase), found " +
                                        std::to_string(fields.size()));
    }
    double values[3] = {0.0, 0.0, 0.0};
    for (int c = 0; c < 3; ++c) {
      if (!core::parseDecimal(fields[static_cast<size_t>(c)], values[c])) {
        throw core::InputError(where, std::string("column '") + kColumnNames[c] + "' is not a number: '" +
                                          fields[static_cast<size_t>(c)] + "'");
      }
      if (!std::isfinite(values[c])) {
        throw core::InputError(where, std::string("column '") + kColumnNames[c] +
                                          "' is not finite: '" + fields[static_cast<size_t>(c)] + "'");
      }
    }
    const double x_m = values[0], amplitude = values[1], phase_rad = values[2];
    if (amplitude < 0.0 || amplitude > 1.0) {
      std::ostringstream s;
      s << "amplitude " << amplitude << " is outside [0, 1]";
      throw core::InputError(where, s.str());
    }
    if (!points.x_m.empty() && !(x_m > points.x_m.back())) {
      std::ostringstream s;
      s.precision(17);
      s << "x = " << x_m << " m is not greater than the previous x = " << points.x_m.back() << " m";
      throw core::InputError(where, s.str());
    }
    points.x_m.push_back(x_m);
    points.amplitude.push_back(amplitude);
    points.phase_rad.push_back(phase_rad);
  }
  if (in.bad()) throw core::InputError(path + ":" + std::to_string(line_no), "read error");
  if (points.x_m.size() < 2) {
    throw core::InputError(path + ":" + std::to_string(line_no),
                           "a profile needs at least 2 data rows, found " +
                               std::to_string(points.x_m.size()) + " (end of file)");
  }
  return points;
}

SampledProfile resampleProfile(const ProfilePoints& points, double dx_m) {
  const std::string where = "resampleProfile";
  core::requirePositive(where + ": dx_m", dx_m);
  const size_t n_points = points.x_m.size();
  if (points.amplitude.size() != n_points || points.phase_rad.size() != n_points) {
    throw core::InputError(where, "x, amplitude and phase columns differ in length");
  }
  if (n_points < 2) throw core::InputError(where, "a profile needs at least 2 points");
  const double x_first = points.x_m.front();
  const double x_last = points.x_m.back();
  const double count = std::floor((x_last - x_first) / dx_m + 1e-9) + 1.0;
  if (!std::isfinite(count) || count > kMaxResampledPoints) {
    std::ostringstream s;
    s << "dx = " << dx_m << " m over a span of " << (x_last - x_first) << " m gives too many samples";
    throw core::InputError(where, s.str());
  }

  SampledProfile profile;
  profile.x0_m = x_first;
  profile.dx_m = dx_m;
  const size_t n = static_cast<size_t>(count);
  profile.t.resize(n);
  size_t seg = 0;  // points.x_m[seg] ≤ x < points.x_m[seg + 1]
  for (size_t j = 0; j < n; ++j) {
    const double x_m = std::min(x_first + static_cast<double>(j) * dx_m, x_last);
    while (seg + 2 < n_points && x_m >= points.x_m[seg + 1]) ++seg;
    const double x_a = points.x_m[seg], x_b = points.x_m[seg + 1];
    const double w = std::clamp((x_m - x_a) / (x_b - x_a), 0.0, 1.0);
    const double amplitude = (1.0 - w) * points.amplitude[seg] + w * points.amplitude[seg + 1];
    const double phase_rad = (1.0 - w) * points.phase_rad[seg] + w * points.phase_rad[seg + 1];
    profile.t[j] = amplitude * std::exp(std::complex<double>(0.0, phase_rad));  // eq:microstructure
  }
  return profile;
}

}  // namespace diffray::wbsdf

namespace diffray::wbsdf {

std::shared_ptr<const WbsdfTable> profileTable(const ProfilePoints& points, double wavelength_m,
                                               std::size_t max_cells) {
  core::requirePositive("--wavelength", wavelength_m);
  if (points.x_m.size() < 2) throw core::InputError("profile", "needs at least 2 points");
  // The discrete pseudo-Wigner repeats every 1/(2dx) in u and folds every component of t beyond 1/(4dx)
  // back into the output (wigner_fft.h). The table keeps |u| < 2/λ, every shift that can leave a propagating
  // ray. dx ≤ λ/32 puts the first fold at 16/λ, so only pairs of components summing to within 4/λ of a
  // multiple of 32/λ can land there; half the smallest input spacing keeps the input's own detail (a phase
  // grating with a sub-wavelength period, a sharp edge given by close points) resolved.
  double min_spacing = points.x_m.back() - points.x_m.front();
  for (std::size_t i = 1; i < points.x_m.size(); ++i)
    min_spacing = std::min(min_spacing, points.x_m[i] - points.x_m[i - 1]);
  const double dx = std::min(wavelength_m / 32.0, 0.5 * min_spacing);
  const double u_keep = 2.0 / wavelength_m;
  const double samples = (points.x_m.back() - points.x_m.front()) / dx + 1.0;
  const double budget = static_cast<double>(max_cells);
  const auto too_long = [&]() {
    std::ostringstream what;  // samples may exceed every integer type: stated as the double it is
    what << "is too long for a Wigner table at this wavelength (" << std::setprecision(4) << samples
         << " samples at dx = " << dx << " m); use a shorter profile or coarser points";
    return core::InputError("profile", what.str());
  };
  if (!(samples * 64.0 <= 4.0 * budget)) throw too_long();
  // Untruncated lags need nu ≥ 2·samples (and at least 64 columns for any profile, however short).
  double nu = 64.0;
  while (nu < 2.0 * samples) nu *= 2.0;
  // Beyond the budget, shorter lags smooth W in u: at most max_cells stored cells (samples × kept columns)
  // and 4·max_cells FFT inputs (samples × nu).
  const auto kept = [&](double n) { return std::min(n, 2.0 * std::ceil(u_keep * 2.0 * n * dx)); };
  while (nu > 64.0 && (samples * kept(nu) > budget || samples * nu > 4.0 * budget)) nu /= 2.0;
  if (samples * kept(nu) > budget) throw too_long();
  return WbsdfTable::fromWigner(wignerFFT(resampleProfile(points, dx), static_cast<int>(nu), u_keep));
}

}  // namespace diffray::wbsdf
