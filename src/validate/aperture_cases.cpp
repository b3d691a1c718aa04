// The aperture cases of `diffray validate`: slits, double slit, rectangle, Fresnel slit and a door.
// Each compares the traced screen with an oracle from diffray::reference.
#include <charconv>
#include <chrono>
#include <cmath>

#include "diffray/core/error.h"
#include "diffray/core/math.h"
#include "diffray/reference/angular_spectrum.h"
#include "diffray/reference/fraunhofer.h"
#include "diffray/reference/fresnel.h"
#include "diffray/reference/rayleigh_sommerfeld.h"
#include "diffray/validate/case.h"
#include "diffray/validate/slit_setup.h"

namespace diffray::validate {

namespace {

double one(const Params& p, const std::string& name) { return p.at(name).at(0); }

int binsOf(const Params& p, const std::string& name) {
  const double b = one(p, name);
  if (!(b >= 3 && b <= 100000 && std::floor(b) == b))
    throw core::InputError("--" + name, "must be a whole number of bins from 3 to 100000");
  return static_cast<int>(b);
}

std::uint64_t raysOf(const RunOptions& o, std::uint64_t fallback) { return o.rays ? o.rays : fallback; }

// Whether --model asks for the angle-impact WBSDF; cases that cannot use it pass two_d = false.
bool modelIsAngleImpact(const RunOptions& o, bool two_d = true) {
  if (o.model == "wigner") return false;
  if (o.model != "angle-impact")
    throw core::InputError("--model", "unknown model '" + o.model + "' (models: wigner, angle-impact)");
  if (!two_d) throw core::InputError("--model", "angle-impact applies to the 2D aperture cases only");
  return true;
}

template <class F>
CaseResult timed(const std::string& name, F&& run) {
  const auto t0 = std::chrono::steady_clock::now();
  CaseResult r;
  r.name = name;
  run(r);
  scoreRows(r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

// The part the single-slit cases share: width, wavelength and distance checked, the slit built, the
// set-up filled. `screen_default(a, λ, z)` is the screen half-width when --screen is 0.
struct SlitCase {
  double a = 0, lambda = 0, z = 0;
  std::shared_ptr<wbsdf::Openings> slit;
  ApertureSetup setup;
};

template <class ScreenDefault>
SlitCase slitCase(const Params& p, const RunOptions& o, ScreenDefault screen_default) {
  SlitCase c;
  c.a = one(p, "width");
  c.lambda = one(p, "wavelength");
  c.z = one(p, "distance");
  core::requirePositive("--width", c.a);
  core::requirePositive("--wavelength", c.lambda);
  core::requirePositive("--distance", c.z);
  c.slit = wbsdf::Openings::slit(c.a);
  c.setup.along_x = c.slit.get();
  c.setup.wavelength_m = c.lambda;
  c.setup.distance_m = c.z;
  c.setup.screen_half_x_m = one(p, "screen") > 0 ? one(p, "screen") : screen_default(c.a, c.lambda, c.z);
  c.setup.bins_x = binsOf(p, "bins");
  c.setup.angle_impact = modelIsAngleImpact(o);
  return c;
}

}  // namespace

CaseInfo slitFraunhoferCase() {
  CaseInfo c{"slit-fraunhofer", "single slit, far field, vs a²·sinc²(a·u) (Fraunhofer)", {}, 32'000'000, {}};
  c.params = {{"width", {100e-6}, "slit width a (m)"},
              {"wavelength", {500e-9}, "wavelength (m)"},
              {"distance", {5.0}, "slit to screen (m); far field needs distance >> a²/λ"},
              {"screen", {0.0}, "screen half-width (m); 0 = three diffraction zeros", 0.0, true},
              {"bins", {151}, "screen bins", 3.0, true}};
  c.param("bins").whole = true;
  c.angle_impact = true;
  c.run = [](const Params& p, const RunOptions& o) {
    return timed("slit-fraunhofer", [&](CaseResult& r) {
      SlitCase sc = slitCase(p, o, [](double a, double lambda, double z) { return 3.0 * lambda * z / a; });
      const double a = sc.a, lambda = sc.lambda, z = sc.z;
      sc.setup.reference = [=](double x, double) {
        return reference::farFieldScreenIntensity2D(x, z, lambda,
                                                    reference::slitFraunhofer(reference::screenU(x, z, lambda), a));
      };
      runAperture(sc.setup, o, raysOf(o, 32'000'000), r);
      r.extra["fresnel_number"] = a * a / (lambda * z);
    });
  };
  return c;
}

CaseInfo doubleSlitCase() {
  CaseInfo c{"double-slit", "two slits, far field, vs 4a²·cos²(πdu)·sinc²(au) (Young)", {}, 32'000'000, {}};
  c.params = {{"width", {50e-6}, "slit width a (m)"},
              {"spacing", {250e-6}, "centre-to-centre spacing d (m)"},
              {"wavelength", {500e-9}, "wavelength (m)"},
              {"distance", {10.0}, "slits to screen (m)"},
              {"screen", {0.0}, "screen half-width (m); 0 = to the envelope's first zero", 0.0, true},
              {"bins", {201}, "screen bins", 3.0, true},
              {"bandwidth", {0.0}, "relative bandwidth: frequencies f0·(1 ± b/2), flat; 0 = monochromatic", 0.0, true, 2.0}};
  c.param("bins").whole = true;
  c.angle_impact = true;
  c.run = [](const Params& p, const RunOptions& o) {
    return timed("double-slit", [&](CaseResult& r) {
      const double a = one(p, "width"), d = one(p, "spacing"), lambda = one(p, "wavelength"),
                   z = one(p, "distance");
      core::requirePositive("--width", a);
      core::requirePositive("--spacing", d);
      core::requirePositive("--wavelength", lambda);
      core::requirePositive("--distance", z);
      const auto slits = wbsdf::Openings::slits(2, a, d);
      ApertureSetup s;
      s.along_x = slits.get();
      s.wavelength_m = lambda;
      s.distance_m = z;
      s.screen_half_x_m = one(p, "screen") > 0 ? one(p, "screen") : lambda * z / a;
      s.bins_x = binsOf(p, "bins");
      const double band = one(p, "bandwidth");
      if (!(band >= 0.0 && band < 2.0)) throw core::InputError("--bandwidth", "must lie in [0, 2)");
      auto mono = [=](double x, double lam) {
        return reference::farFieldScreenIntensity2D(x, z, lam,
                                                    reference::doubleSlitFraunhofer(reference::screenU(x, z, lam), a, d));
      };
      if (band > 0.0) {
        // Frequencies f0(1 ± b/2), flat: the pattern averaged over 1/λ (16-point Gauss–Legendre).
        s.wavelength_m = lambda / (1.0 + 0.5 * band);
        s.wavelength_max_m = lambda / (1.0 - 0.5 * band);
        s.reference = [=](double x, double) {
          const auto& gl = core::gaussLegendre(16);
          double sum = 0.0;
          for (int i = 0; i < 16; ++i) sum += 0.5 * gl.weights[i] * mono(x, lambda / (1.0 + 0.5 * band * gl.nodes[i]));
          return sum;
        };
      } else {
        s.reference = [=](double x, double) { return mono(x, lambda); };
      }
      s.angle_impact = modelIsAngleImpact(o);
      runAperture(s, o, raysOf(o, 32'000'000), r);
    });
  };
  return c;
}

CaseInfo rectApertureCase() {
  CaseInfo c{"rect-aperture", "rectangular aperture on a 2D screen vs (ab/λz)²·sinc²·sinc²", {}, 32'000'000, {}};
  c.params = {{"width", {100e-6}, "aperture width a along x (m)"},
              {"height", {150e-6}, "aperture height b along y (m)"},
              {"wavelength", {500e-9}, "wavelength (m)"},
              {"distance", {5.0}, "aperture to screen (m)"},
              {"bins", {41}, "screen bins along each axis", 3.0, true}};
  c.param("bins").whole = true;
  c.run = [](const Params& p, const RunOptions& o) {
    return timed("rect-aperture", [&](CaseResult& r) {
      const double a = one(p, "width"), b = one(p, "height"), lambda = one(p, "wavelength"),
                   z = one(p, "distance");
      core::requirePositive("--width", a);
      core::requirePositive("--height", b);
      core::requirePositive("--wavelength", lambda);
      core::requirePositive("--distance", z);
      const auto sx = wbsdf::Openings::slit(a);
      const auto sy = wbsdf::Openings::slit(b);
      ApertureSetup s;
      s.along_x = sx.get();
      s.along_y = sy.get();
      s.wavelength_m = lambda;
      s.distance_m = z;
      s.screen_half_x_m = 2.0 * lambda * z / a;
      s.screen_half_y_m = 2.0 * lambda * z / b;
      s.bins_x = s.bins_y = binsOf(p, "bins");
      s.reference = [=](double x, double y) {
        // 3D far field: |T(u,v)|²·cos²θ/(λr)², u = x/(rλ), v = y/(rλ).
        const double rr = std::sqrt(x * x + y * y + z * z);
        const double t2 = reference::rectFraunhofer(x / (rr * lambda), y / (rr * lambda), a, b);
        return t2 * (z / rr) * (z / rr) / (lambda * rr * lambda * rr);
      };
      modelIsAngleImpact(o, false);
      runAperture(s, o, raysOf(o, 32'000'000), r);
    });
  };
  return c;
}

CaseInfo slitFresnelCase() {
  CaseInfo c{"slit-fresnel", "slit in the near field (Fresnel number ~4) vs the Fresnel-integral pattern", {},
             16'000'000, {}};
  c.params = {{"width", {1e-3}, "slit width a (m)"},
              {"wavelength", {500e-9}, "wavelength (m)"},
              {"distance", {0.5}, "slit to screen (m); Fresnel number a²/(λz)"},
              {"screen", {0.0}, "screen half-width (m); 0 = 1.5 a", 0.0, true},
              {"bins", {151}, "screen bins", 3.0, true}};
  c.param("bins").whole = true;
  c.angle_impact = true;
  c.run = [](const Params& p, const RunOptions& o) {
    return timed("slit-fresnel", [&](CaseResult& r) {
      SlitCase sc = slitCase(p, o, [](double a, double, double) { return 1.5 * a; });
      const double a = sc.a, lambda = sc.lambda, z = sc.z;
      sc.setup.reference = [=](double x, double) { return reference::fresnelSlitIntensity(x, a, lambda, z); };
      runAperture(sc.setup, o, raysOf(o, 16'000'000), r);
      r.extra["fresnel_number"] = a * a / (lambda * z);
    });
  };
  return c;
}

CaseInfo doorRsCase() {
  CaseInfo c{"door-rs", "0.9 m doorway (2D), line 2 m behind, vs Rayleigh–Sommerfeld quadrature", {}, 32'000'000,
             {}};
  // Bounds keep the references' quadratures (∝ width/λ per point) to seconds: an acoustic doorway, audio
  // frequencies.
  c.params = {{"width", {0.9}, "opening width (m)", 0.0, false, 50.0},
              {"freq", {125, 250, 500, 1000}, "frequencies (Hz), comma-separated, up to 20 kHz", 0.0, false, 20000.5},
              {"distance", {2.0}, "opening to the observation line (m)", 1e-6, true, 1000.0},
              {"screen", {3.0}, "half-length of the observation line (m)", 0.0, false, 100.0},
              {"bins", {121}, "bins along the line", 3.0, true},
              {"temperature", {20.0}, "air temperature (°C), sets the speed of sound", -273.15}};
  c.param("freq").list = true;
  c.param("bins").whole = true;
  c.angle_impact = true;
  c.run = [](const Params& p, const RunOptions& o) {
    return timed("door-rs", [&](CaseResult& r) {
      const double a = one(p, "width"), z = one(p, "distance");
      core::requirePositive("--width", a);
      core::requirePositive("--distance", z);
      core::requirePositive("--screen", one(p, "screen"));
      const double c_air = core::speedOfSound(one(p, "temperature"));
      const auto door = wbsdf::Openings::slit(a);
      const std::uint64_t rays = raysOf(o, 32'000'000);
      const auto& freqs = p.at("freq");
      for (std::size_t i = 0; i < freqs.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
          if (freqs[i] == freqs[j]) throw core::InputError("--freq", "lists a frequency twice");
      for (double f : freqs) {
        core::requirePositive("--freq", f);
        const double lambda = c_air / f;
        ApertureSetup s;
        s.along_x = door.get();
        s.wavelength_m = lambda;
        s.distance_m = z;
        s.screen_half_x_m = one(p, "screen");
        s.bins_x = binsOf(p, "bins");
        s.angle_impact = modelIsAngleImpact(o);
        const std::vector<std::pair<double, double>> opening{{-0.5 * a, 0.5 * a}};
        s.reference = [=](double x, double) {
          return reference::rayleighSommerfeldIntensity2D(opening, x, z, lambda);
        };
        s.alt_reference = [=](double x, double) {
          return reference::propagatingIntensity2D(opening, x, z, lambda);
        };
        CaseResult part;
        runAperture(s, o, rays / freqs.size(), part);
        // The shortest text that reads back as f: distinct frequencies keep distinct patterns (a stream's
        // 6 significant digits merged 1000.0001 Hz into 1000 Hz).
        char digits[32];
        const std::to_chars_result written = std::to_chars(digits, digits + sizeof digits, f);
        const std::string label = "f=" + std::string(digits, written.ptr) + "Hz";
        for (Row row : part.rows) {
          row.label = label;
          r.rows.push_back(row);
        }
        r.rays += part.rays;
        r.negative_energy_fraction = std::max(r.negative_energy_fraction, part.negative_energy_fraction);
        for (const auto& [k, v] : part.extra) r.extra[k + "[" + label + "]"] = v;
        // The same rays against the propagating field alone (no evanescent near field): what an exact
        // straight-ray transport can reach.
        double peak = 0.0, worst = 0.0;
        for (const Row& row : part.rows) peak = std::max(peak, row.alt_reference);
        for (const Row& row : part.rows) worst = std::max(worst, std::abs(row.traced - row.alt_reference) / peak);
        r.extra["max_abs_error_vs_propagating_rel_peak[" + label + "]"] = worst;
      }
    });
  };
  return c;
}

}  // namespace diffray::validate
