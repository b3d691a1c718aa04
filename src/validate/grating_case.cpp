// `diffray validate grating-orders`: a sinusoidal phase grating under a plane wave; the energy in each
// diffraction order against J_q(m/2)² (paper eq. for the sinusoidal grating; design.md §1), and the
// orders' directions against the grating equation sinθ_q = qλ/Λ.
#include <chrono>
#include <cmath>

#include "diffray/core/error.h"
#include "diffray/reference/fraunhofer.h"
#include "diffray/transport/tracer.h"
#include "diffray/validate/case.h"

namespace diffray::validate {

CaseInfo gratingOrdersCase() {
  CaseInfo c{"grating-orders", "sinusoidal phase grating: energy per order vs J_q(m/2)²", {}, 4'000'000, {}};
  c.params = {{"period", {1.6e-6}, "grating period Λ (m); a CD's track pitch is 1.6 µm"},
              {"modulation", {2.0}, "phase modulation m: t = exp(i(m/2)·sin(2πx/Λ))"},
              {"wavelength", {500e-9}, "wavelength (m)"},
              {"periods", {64}, "illuminated periods"}};
  c.run = [](const Params& p, const RunOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    if (o.model != "wigner") throw core::InputError("--model", "grating-orders takes the wigner model only");
    const double period = p.at("period")[0], m = p.at("modulation")[0], lambda = p.at("wavelength")[0];
    const double periods = p.at("periods")[0];
    core::requirePositive("--period", period);
    core::requirePositive("--wavelength", lambda);
    if (!(periods >= 1 && std::floor(periods) == periods))
      throw core::InputError("--periods", "must be a whole number >= 1");

    wbsdf::PhaseGrating grating(period, m);
    wbsdf::TableOptions topts;
    topts.wavelength_m = lambda;
    transport::Scene scene;
    transport::Occluder occ;
    occ.table_x = wbsdf::WbsdfTable::build(grating, topts);
    const double lit = periods * period;
    occ.half_x_m = lit;
    occ.half_y_m = 1.0;
    scene.addOccluder(occ);
    // A flat screen 1 m behind, wide enough for directions up to |sinθ| = 0.985.
    const double z = 1.0;
    receiver::Screen screen;
    screen.frame.origin = core::Vec3(0, 0, z);
    screen.half_x_m = 6.0;
    screen.half_y_m = 1.0;
    screen.nx = 12000;
    screen.ny = 1;
    scene.addScreen(screen);
    scene.build();

    transport::CollimatedSource src;
    src.frame.origin = core::Vec3(0.5 * lit, 0, -0.1);
    src.half_x_m = 0.5 * lit;
    src.half_y_m = 0.5;
    src.wavelength_m = lambda;
    transport::TraceOptions to;
    to.rays = o.rays ? o.rays : 4'000'000;
    to.seed = o.seed;
    to.qmc = o.qmc;
    to.on_progress = o.on_progress;
    const transport::TraceResult tr = transport::trace(scene, src, to);

    // Group bins by the order whose direction they are nearest to (within a quarter of the order spacing
    // in sinθ); the rest hold the half-order lines, which must cancel over whole periods.
    const int q_max = static_cast<int>(std::floor(period / lambda));
    std::vector<double> order_e(2 * q_max + 1, 0.0), order_var(2 * q_max + 1, 0.0);
    double between = 0.0;
    const auto& tally = tr.screens[0];
    for (int ix = 0; ix < screen.nx; ++ix) {
      const double x = screen.binCentreX(ix);
      const double sin_t = x / std::hypot(x, z);
      const double q_real = sin_t * period / lambda;
      const int q = static_cast<int>(std::lround(q_real));
      const double se = tally.standardError(ix);
      if (std::abs(q_real - q) < 0.25 && std::abs(q) <= q_max) {
        order_e[q + q_max] += tally.sum[ix];
        order_var[q + q_max] += se * se;
      } else {
        between += tally.sum[ix];
      }
    }
    CaseResult r;
    r.name = "grating-orders";
    r.rays = tr.rays;
    double evanescent_ref = 1.0;
    for (int q = -q_max; q <= q_max; ++q) {
      Row row;
      row.label = "";
      row.x_m = q * lambda / period;  // sinθ of the order
      row.traced = order_e[q + q_max] / tr.emitted;
      row.std_error = std::sqrt(order_var[q + q_max]) / tr.emitted;
      row.reference = reference::phaseGratingOrderEfficiency(q, m);
      evanescent_ref -= row.reference;
      r.rows.push_back(row);
    }
    r.negative_energy_fraction = tally.negativeFraction();
    r.extra["half_order_energy"] = between / tr.emitted;
    r.extra["energy_evanescent"] = tr.evanescent / tr.emitted;
    r.extra["energy_evanescent_reference"] = evanescent_ref;
    r.extra["energy_escaped"] = tr.escaped / tr.emitted;
    scoreRows(r);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  };
  return c;
}

}  // namespace diffray::validate
