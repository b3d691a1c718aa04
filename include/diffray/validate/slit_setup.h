#pragma once
// The common set-up of the aperture cases: a plane wave at normal incidence on an occluder in the plane
// z = 0 (local x across the openings, y along them), a screen parallel to it at distance z, and a
// comparison of the screen's flux per unit area with a reference intensity averaged over each bin.
// For 2D problems (no y table) the source window, occluder and screen are a strip of height 1 m and the
// screen has one bin along y. Units: metres, intensity relative to the incident plane wave.
#include <functional>
#include <memory>

#include "diffray/validate/case.h"
#include "diffray/wbsdf/microstructure.h"
#include "diffray/wbsdf/table.h"

namespace diffray::validate {

struct ApertureSetup {
  const wbsdf::Microstructure* along_x = nullptr;
  const wbsdf::Microstructure* along_y = nullptr;  ///< null: a 2D problem, uniform along y
  double wavelength_m = 0;
  double wavelength_max_m = 0;  ///< > wavelength_m: a band, flat in frequency (transport::CollimatedSource)
  double distance_m = 0;       ///< occluder to screen
  double screen_half_x_m = 0, screen_half_y_m = 0;
  int bins_x = 1, bins_y = 1;
  int max_rows_per_feature = 1024;
  /// Use the angle-impact WBSDF (wbsdf/angle_impact.h, exact straight-ray transport in 2D) with an
  /// intensity screen instead of the Wigner distribution with a flux screen. 2D set-ups of Openings only.
  bool angle_impact = false;
  /// Reference intensity at screen point (x, y), relative to the incident intensity.
  std::function<double(double, double)> reference;
  /// Optional second oracle, averaged over each bin like the first (Row::alt_reference).
  std::function<double(double, double)> alt_reference;
};

/// Traces the set-up and fills rows (one per bin) and the energy balance into `result.extra`.
void runAperture(const ApertureSetup& setup, const RunOptions& options, std::uint64_t rays, CaseResult& result);

}  // namespace diffray::validate
