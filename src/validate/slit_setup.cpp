#include "diffray/validate/slit_setup.h"

#include <algorithm>
#include <cmath>

#include "diffray/core/error.h"
#include "diffray/core/math.h"
#include "diffray/transport/tracer.h"
#include "diffray/wbsdf/angle_impact.h"

namespace diffray::validate {

namespace {

// Shifts beyond this land outside the screen, so they need not be tabulated: the table stays small and
// every ray it draws can reach a bin. The truncated mass is reported in the energy balance.
double usefulShiftRange(double wavelength, double screen_half, double support_half, double distance) {
  const double reach = screen_half + support_half;
  const double sin_max = reach / std::hypot(reach, distance);
  return std::min(2.0 / wavelength, 1.25 * sin_max / wavelength + 8.0 / (2.0 * support_half));
}

// A u-cell of width du blurs landing positions by up to λ·z·du: this du keeps that under 1/8 of a bin.
double cellWidthU(const ApertureSetup& s, double bin_m) { return bin_m / (8.0 * s.wavelength_m * s.distance_m); }

std::shared_ptr<const wbsdf::WbsdfTable> tableFor(const wbsdf::Microstructure& m, const ApertureSetup& s,
                                                  double screen_half, int bins) {
  const auto [lo, hi] = m.support();
  wbsdf::TableOptions o;
  o.wavelength_m = s.wavelength_m;
  // Rows: an x-cell of width dx moves where a ray's direction was drawn by up to dx; keep that under 1/8 of
  // a bin and of the smallest feature.
  const double bin_m = 2.0 * screen_half / bins;
  const double dx = std::min(bin_m, m.featureSize()) / 8.0;
  o.rows_per_feature =
      std::max(8, std::min(s.max_rows_per_feature, core::checkedCount("table rows", m.featureSize() / dx, 1e9)));
  const double du = cellWidthU(s, bin_m);
  o.cells_per_coherence =
      std::max(o.cells_per_coherence, core::checkedCount("table columns", 1.0 / (du * m.coherenceLength()), 1e9));
  o.u_half_range_per_m = usefulShiftRange(s.wavelength_m, screen_half, 0.5 * (hi - lo), s.distance_m);
  return wbsdf::WbsdfTable::build(m, o);
}

}  // namespace

void runAperture(const ApertureSetup& s, const RunOptions& options, std::uint64_t rays, CaseResult& result) {
  DIFFRAY_CHECK(s.along_x && s.reference);
  core::requirePositive("--wavelength", s.wavelength_m);
  core::requirePositive("--distance", s.distance_m);
  const bool two_d = s.along_y == nullptr;

  transport::Scene scene;
  transport::Occluder occ;
  if (s.angle_impact) {
    const auto* openings = dynamic_cast<const wbsdf::Openings*>(s.along_x);
    DIFFRAY_CHECK(openings != nullptr && two_d);
    const auto [lo, hi] = openings->support();
    wbsdf::AngleImpactOptions ai;
    ai.wavelength_m = s.wavelength_m;
    ai.x_lo_m = lo;
    ai.x_hi_m = hi;
    // Same resolution rules as the Wigner tables: cells move a ray by at most 1/8 of a bin.
    const double bin_m = 2.0 * s.screen_half_x_m / s.bins_x;
    ai.margin_m = 4.0 * s.wavelength_m;
    ai.nx = core::checkedCount("angle-impact table rows",
                               (hi - lo + 2.0 * ai.margin_m) / (std::min(bin_m, hi - lo) / 8.0), 1e7);
    ai.u_half_range_per_m = usefulShiftRange(s.wavelength_m, s.screen_half_x_m, 0.5 * (hi - lo), s.distance_m);
    ai.nu = core::checkedCount("angle-impact table columns",
                               2.0 * ai.u_half_range_per_m / cellWidthU(s, bin_m), 1e7);
    occ.table_x = wbsdf::angleImpactTable(
        [openings](double u) { return wbsdf::openingsSpectrum(*openings, u); }, ai);
  } else {
    occ.table_x = tableFor(*s.along_x, s, s.screen_half_x_m, s.bins_x);
  }
  if (!two_d) occ.table_y = tableFor(*s.along_y, s, s.screen_half_y_m, s.bins_y);
  const double x0 = occ.table_x->layout().x0_m;
  const double x1 = x0 + occ.table_x->layout().nx * occ.table_x->layout().dx_m;
  const auto [y0, y1] = two_d ? std::pair<double, double>{-0.5, 0.5} : s.along_y->support();
  occ.half_x_m = 1.5 * std::max(std::abs(x0), std::abs(x1));
  occ.half_y_m = 1.5 * std::max(std::abs(y0), std::abs(y1));
  scene.addOccluder(occ);

  receiver::Screen screen;
  screen.frame.origin = core::Vec3(0, 0, s.distance_m);
  screen.half_x_m = s.screen_half_x_m;
  screen.half_y_m = two_d ? 0.6 : s.screen_half_y_m;
  screen.nx = s.bins_x;
  screen.ny = two_d ? 1 : s.bins_y;
  screen.intensity = s.angle_impact;
  scene.addScreen(screen);
  scene.build();

  // The plane wave illuminates exactly the table's support: light elsewhere would be absorbed anyway.
  transport::CollimatedSource src;
  src.frame.origin = core::Vec3(0.5 * (x0 + x1), 0.5 * (y0 + y1), -0.1 * s.distance_m);
  src.half_x_m = 0.5 * (x1 - x0);
  src.half_y_m = 0.5 * (y1 - y0);
  src.wavelength_m = s.wavelength_m;
  src.wavelength_max_m = s.wavelength_max_m;
  transport::TraceOptions topt;
  topt.rays = rays;
  topt.seed = options.seed;
  topt.qmc = options.qmc;
  topt.on_progress = options.on_progress;
  const transport::TraceResult tr = transport::trace(scene, src, topt);

  // Flux per unit screen area. In 2D the strip is 1 m tall, so energy per bin width is per metre.
  const receiver::ScreenTally& tally = tr.screens[0];
  const double bin_area = screen.binWidthX() * (two_d ? (y1 - y0) : screen.binWidthY());
  const auto& gl = core::gaussLegendre(8);
  const int ny_ref = two_d ? 1 : 8;
  for (int iy = 0; iy < screen.ny; ++iy) {
    for (int ix = 0; ix < screen.nx; ++ix) {
      const int bin = ix + screen.nx * iy;
      Row row;
      row.x_m = screen.binCentreX(ix);
      row.y_m = two_d ? 0.0 : screen.binCentreY(iy);
      row.traced = tally.sum[bin] / bin_area;
      row.std_error = tally.standardError(bin) / bin_area;
      // The oracle averaged over the bin (Gauss–Legendre in x, and in y for 2D screens).
      auto binAverage = [&](const std::function<double(double, double)>& f) {
        double ref = 0.0;
        for (int i = 0; i < 8; ++i)
          for (int j = 0; j < ny_ref; ++j) {
            const double x = row.x_m + 0.5 * screen.binWidthX() * gl.nodes[i];
            const double y = two_d ? 0.0 : row.y_m + 0.5 * screen.binWidthY() * gl.nodes[j];
            ref += 0.5 * gl.weights[i] * (two_d ? 1.0 : 0.5 * gl.weights[j]) * f(x, y);
          }
        return ref;
      };
      row.reference = binAverage(s.reference);
      if (s.alt_reference) row.alt_reference = binAverage(s.alt_reference);
      result.rows.push_back(row);
    }
  }
  result.rays = tr.rays;
  result.negative_energy_fraction = tally.negativeFraction();
  double on_screen = 0.0;
  for (double v : tally.sum) on_screen += v;
  const double p = tr.emitted;
  result.extra["energy_on_screen"] = on_screen / p;
  result.extra["energy_absorbed"] = tr.absorbed / p;
  result.extra["energy_evanescent"] = tr.evanescent / p;
  result.extra["energy_escaped"] = tr.escaped / p;
  result.extra["table_truncated_mass"] = occ.table_x->truncatedMass();
  result.extra["table_negative_fraction"] = occ.table_x->negativeFraction();
  result.extra["table_cells"] = static_cast<double>(occ.table_x->layout().nx) * occ.table_x->layout().nu;
  result.extra["segments_per_ray"] = static_cast<double>(tr.segments) / static_cast<double>(tr.rays);
}

}  // namespace diffray::validate
